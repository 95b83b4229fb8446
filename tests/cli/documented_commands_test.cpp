// Every countershade command line that README.md and docs/*.md show in a code block names a real
// subcommand and only flags that subcommand (or the method it names) accepts. The docs' examples
// are what users copy; a renamed flag must not leave them broken.

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "test_util.h"

namespace countershade {
namespace {

using testing::read_file;
using testing::run_cli;
using testing::source_dir;

// One command line as a document shows it (continuation lines joined).
struct DocumentedCommand {
  std::string where;  // file:line
  std::vector<std::string> tokens;
};

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

bool is_binary(const std::string& word) {
  return word == "countershade" || (word.size() > 13 && word.ends_with("/countershade"));
}

// The words from the binary on, up to a comment or the end of a shell command.
std::vector<std::string> command_words(const std::vector<std::string>& words) {
  std::vector<std::string> out;
  bool started = false;
  for (const std::string& w : words) {
    if (!started && !is_binary(w)) continue;
    if (started && (w.starts_with("#") || w == "&&" || w == ";" || w == ">" || w == "2>&1")) break;
    started = true;
    out.push_back(w);
  }
  return out;
}

void collect_commands(const std::filesystem::path& file, std::vector<DocumentedCommand>& out) {
  for (const testing::CodeBlock& block : testing::markdown_code_blocks(file)) {
    std::string joined;
    int first_line = 0;
    for (size_t i = 0; i < block.lines.size(); ++i) {
      const std::string& line = block.lines[i];
      if (joined.empty()) first_line = block.first_line + int(i);
      const bool continues = !line.empty() && line.back() == '\\';
      joined += (continues ? line.substr(0, line.size() - 1) : line) + " ";
      if (continues) continue;
      std::vector<std::string> words = command_words(split_words(joined));
      joined.clear();
      if (words.size() >= 2)
        out.push_back(
            {file.filename().string() + ":" + std::to_string(first_line), std::move(words)});
    }
  }
}

std::vector<DocumentedCommand> documented_commands() {
  std::vector<DocumentedCommand> commands;
  collect_commands(source_dir() / "README.md", commands);
  for (const auto& entry : std::filesystem::directory_iterator(source_dir() / "docs"))
    if (entry.path().extension() == ".md") collect_commands(entry.path(), commands);
  return commands;
}

// A flag as written, reduced to its name: "[--spp" -> "--spp", "--kernel=5%" -> "--kernel".
std::string flag_name(const std::string& word) {
  size_t begin = word.find("--");
  if (begin == std::string::npos || word.find('<') != std::string::npos) return "";
  std::string name = word.substr(begin);
  name = name.substr(0, name.find_first_of("=])|,`'\""));
  return name.size() > 2 ? name : "";
}

// What a subcommand's --help accepts: its own options, and per method the method's parameters.
struct AcceptedFlags {
  bool exists = false;
  std::set<std::string> options;
  std::map<std::string, std::set<std::string>> method_flags;
};

// The sections of --help that name flags: "Options:" and "Filter keys:" (the subcommand's own)
// and "Method parameters" (one line per method). The examples section is left out: it only uses
// flags.
AcceptedFlags accepted_flags(const std::string& subcommand) {
  AcceptedFlags accepted;
  const auto help = run_cli(subcommand + " --help");
  accepted.exists = help.exit_code == 0;
  const std::regex flag(R"(--[a-z0-9][a-z0-9-]*)"), method_line(R"(^  ([a-z0-9-]+): (--.*)$)");
  std::istringstream in(help.output);
  enum class Section { other, options, methods } section = Section::other;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != ' ') {
      const bool own = line.starts_with("Options:") || line.starts_with("Filter keys:");
      section = own                                     ? Section::options
                : line.starts_with("Method parameters") ? Section::methods
                                                        : Section::other;
      if (!line.starts_with("Filter keys:")) continue;  // its flags start on the header line
    }
    std::smatch m;
    std::set<std::string>* into = nullptr;
    if (section == Section::options) into = &accepted.options;
    if (section == Section::methods && std::regex_match(line, m, method_line))
      into = &accepted.method_flags[m[1].str()];
    if (!into) continue;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), flag);
         it != std::sregex_iterator(); ++it)
      into->insert(it->str());
  }
  return accepted;
}

// Why `flag` is wrong in `command` ("" when the subcommand takes it).
std::string check_flag(const std::string& flag, const std::vector<std::string>& words,
                       const AcceptedFlags& accepted) {
  if (accepted.options.count(flag)) return "";
  auto method_at = std::find(words.begin(), words.end(), "--method");
  if (method_at == words.end() || method_at + 1 == words.end()) {
    // A synopsis without a method: any method's parameter may stand there.
    for (const auto& [method, flags] : accepted.method_flags)
      if (flags.count(flag)) return "";
    return "is not an option of this subcommand";
  }
  const std::string method = *(method_at + 1);
  if (!accepted.method_flags.count(method))
    return "names method '" + method + "', which the subcommand does not list";
  const std::set<std::string>& flags = accepted.method_flags.at(method);
  const bool negated = flag.starts_with("--no-") && flags.count("--" + flag.substr(5));
  return flags.count(flag) || negated
             ? ""
             : "is neither an option of this subcommand nor a parameter of " + method;
}

TEST(DocumentedCommands, EveryCommandInTheDocsUsesOnlyFlagsItsSubcommandAccepts) {
  const std::vector<DocumentedCommand> commands = documented_commands();
  ASSERT_GT(commands.size(), 40u) << "the docs show dozens of commands; the scan found too few";
  std::map<std::string, AcceptedFlags> help_of;
  size_t flags_checked = 0;
  for (const DocumentedCommand& c : commands) {
    const std::string subcommand = c.tokens[1].starts_with("-") ? "" : c.tokens[1];
    if (subcommand.find_first_of("<[(") != std::string::npos) continue;  // a placeholder
    if (!help_of.count(subcommand)) help_of[subcommand] = accepted_flags(subcommand);
    const AcceptedFlags& accepted = help_of.at(subcommand);
    EXPECT_TRUE(accepted.exists) << c.where << ": no subcommand '" << subcommand << "'";
    if (!accepted.exists) continue;
    for (const std::string& word : c.tokens) {
      const std::string flag = flag_name(word);
      if (flag.empty()) continue;
      ++flags_checked;
      const std::string problem = check_flag(flag, c.tokens, accepted);
      EXPECT_EQ(problem, "") << c.where << ": countershade " << subcommand << " " << flag;
    }
  }
  EXPECT_GT(flags_checked, 100u);
}

// The check itself: a flag no subcommand has, or a method parameter given to the wrong method,
// is caught.
TEST(DocumentedCommands, TheCheckRejectsAnUnknownFlagAndAParameterOfAnotherMethod) {
  const AcceptedFlags render = accepted_flags("render");
  ASSERT_TRUE(render.exists);
  const std::vector<std::string> usm3d =
      split_words("countershade render s.json -o x.png --method usm3d --sigma 0.1");
  EXPECT_EQ(check_flag("--sigma", usm3d, render), "");
  EXPECT_EQ(check_flag("--no-adapt", usm3d, render), "");
  EXPECT_NE(check_flag("--kernel", usm3d, render), "");
  EXPECT_NE(check_flag("--colour", usm3d, render), "");
  EXPECT_FALSE(accepted_flags("rendr").exists);
  EXPECT_EQ(flag_name("[--spp"), "--spp");
  EXPECT_EQ(flag_name("--kernel=5%"), "--kernel");
  EXPECT_EQ(flag_name("--<parameter>"), "");
}

}  // namespace
}  // namespace countershade
