// 16-bit stimuli in the browser. A canvas shows 8 bits, so each frame the page draws every image
// from its 16-bit codes (an integer texture) through the app's seeded dither (src/runtime/
// fine_levels: its GLSL, its thresholds and stride, its seed hashing, all taken from the engine):
// each pixel shows one of the two 8-bit levels around its value, and its mean over 64 consecutive
// frames is that value. One WebGL2 canvas lies over the page, one canvas pixel per device pixel.

const VERTEX = `#version 300 es
in vec2 corner;
uniform vec4 rect; // x, y, width, height in clip space
void main() { gl_Position = vec4(rect.xy + corner * rect.zw, 0.0, 1.0); }`;

// The app's fragment shader for the dither path, on an integer texture instead of split bytes.
function fragmentSource(fineLevelsGlsl) {
  return `#version 300 es
precision highp float;
precision highp int;
precision highp usampler2D;
${fineLevelsGlsl}
uniform usampler2D image;
uniform ivec2 top_left; // the image's top-left pixel: x, and y of its top row counted from the bottom
uniform uint frame;
uniform uint seed_mix;
out vec4 colour;
void main() {
  uvec2 p = uvec2(int(gl_FragCoord.x) - top_left.x, top_left.y - int(gl_FragCoord.y));
  uvec3 v = texelFetch(image, ivec2(p), 0).rgb;
  colour = vec4(vec3(dither_level(v, dither_threshold(p.x, p.y, frame, seed_mix))) / 255.0, 1.0);
}`;
}

function compile(gl, kind, source) {
  const shader = gl.createShader(kind);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
  return shader;
}

export class DeepImages {
  // Throws when the browser has no WebGL2 (the page then says so and records nothing).
  constructor(engine, parent, sessionSeed) {
    this.canvas = document.createElement("canvas");
    Object.assign(this.canvas.style, { position: "fixed", left: "0", top: "0", zIndex: "1", pointerEvents: "none" });
    const gl = this.canvas.getContext("webgl2", { antialias: false, premultipliedAlpha: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error("this browser has no WebGL2");
    this.gl = gl;
    this.seedMix = engine.ditherSeedMix(String(sessionSeed));
    this.program = gl.createProgram();
    gl.attachShader(this.program, compile(gl, gl.VERTEX_SHADER, VERTEX));
    gl.attachShader(this.program, compile(gl, gl.FRAGMENT_SHADER, fragmentSource(engine.fineLevelsGlsl())));
    gl.linkProgram(this.program);
    if (!gl.getProgramParameter(this.program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(this.program));
    gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, 0, 1, 0, 0, 1, 1, 1]), gl.STATIC_DRAW);
    const corner = gl.getAttribLocation(this.program, "corner");
    gl.enableVertexAttribArray(corner);
    gl.vertexAttribPointer(corner, 2, gl.FLOAT, false, 0, 0);
    this.uniforms = Object.fromEntries(["rect", "image", "top_left", "frame", "seed_mix"].map((n) => [n, gl.getUniformLocation(this.program, n)]));
    this.textures = new Map();
    this.items = []; // what the next frames show (layout.js's placeImages sets them)
    this.frame = 0;  // frames drawn: the dither's frame number
    parent.appendChild(this.canvas);
  }

  // Draws the next frame of the current items; a test may ask for the pixels of the first item
  // over the next n frames that show one (window.countershadeDitherCapture = {frames: n}).
  drawNext() {
    this.draw(this.frame, this.items);
    const capture = window.countershadeDitherCapture;
    if (capture && this.items.length && (capture.taken ??= []).length < capture.frames) {
      const pixels = this.readItem(this.items[0]);
      capture.taken.push({ frame: this.frame, item: this.items[0], pixels: btoa(String.fromCharCode(...pixels)) });
    }
    ++this.frame;
  }

  // Fetches an image's 16-bit codes (export-web's .rgb16 file: width × height × RGB, little-endian,
  // top row first) into a texture.
  async load(file, width, height) {
    const response = await fetch(file);
    if (!response.ok) throw new Error(`${file}: ${response.status}`);
    const codes = new Uint16Array(await response.arrayBuffer());
    if (codes.length !== width * height * 3) throw new Error(`${file}: not ${width}×${height} RGB codes`);
    const gl = this.gl, texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 2);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGB16UI, width, height, 0, gl.RGB_INTEGER, gl.UNSIGNED_SHORT, codes);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    this.textures.set(file, texture);
  }

  // One frame: the canvas covers the window in device pixels; each item ({file, x, y, width,
  // height}, device pixels from the top-left) is drawn through the dither at `frame`.
  draw(frame, items) {
    const gl = this.gl, dpr = window.devicePixelRatio;
    const W = Math.round(window.innerWidth * dpr), H = Math.round(window.innerHeight * dpr);
    if (this.canvas.width !== W || this.canvas.height !== H) {
      Object.assign(this.canvas, { width: W, height: H });
      Object.assign(this.canvas.style, { width: `${W / dpr}px`, height: `${H / dpr}px` });
    }
    gl.viewport(0, 0, W, H);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    gl.useProgram(this.program);
    gl.uniform1ui(this.uniforms.frame, frame >>> 0);
    gl.uniform1ui(this.uniforms.seed_mix, this.seedMix);
    gl.uniform1i(this.uniforms.image, 0);
    for (const { file, x, y, width, height } of items) {
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, this.textures.get(file));
      gl.uniform4f(this.uniforms.rect, (2 * x) / W - 1, 1 - (2 * (y + height)) / H, (2 * width) / W, (2 * height) / H);
      gl.uniform2i(this.uniforms.top_left, x, H - 1 - y);
      gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4);
    }
    this.lastFrame = { frame, items, W, H };
  }

  // The last frame's pixels of an item (RGBA, top row first), for the tests.
  readItem(item) {
    const gl = this.gl, { width, height } = item;
    const bottomUp = new Uint8Array(width * height * 4);
    gl.readPixels(item.x, this.lastFrame.H - item.y - height, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bottomUp);
    const out = new Uint8Array(bottomUp.length);
    for (let r = 0; r < height; ++r) out.set(bottomUp.subarray((height - 1 - r) * width * 4, (height - r) * width * 4), r * width * 4);
    return out;
  }
}
