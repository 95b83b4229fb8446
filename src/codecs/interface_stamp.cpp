// The interface a codec library was built for (a stamp of codecs/*.h that the build defines as
// COUNTERSHADE_PLUGIN_INTERFACE): the program refuses a library built for another
// (core/plugin_library.cpp). Every codec library compiles this one file.

extern "C" __attribute__((visibility("default"))) const char* countershade_plugin_interface() {
  return COUNTERSHADE_PLUGIN_INTERFACE;
}
