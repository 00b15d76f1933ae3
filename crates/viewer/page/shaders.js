// @ts-check
// godel view: the GLSL ES 3.00 shaders. SHADE_FS reproduces the `shade` crate's per-pixel
// rule (crates/shade/src/shading.rs: texture, time, frequency and light layers multiplied,
// the Lambert factor, status colours, 8-bit sRGB) and, in look mode, the remapping of
// the `look` crate (camera direction → aberration → the sphere read smoothly: bilinear within
// one image of one object, nearest elsewhere; g times the Doppler factor), with s×s samples
// per pixel. For an anti-aliased file (s×s samples per pixel) it colours each sample and
// averages the linear colours of a pixel's samples before encoding (a box filter). It writes
// one texel per output pixel into an offscreen RGBA8 texture, row 0 of the picture in
// texture row 0; the display pass (displaySource) then draws that texture on the
// canvas, scaled with trilinear filtering. The polarization layer's ticks are drawn over the
// shaded pixels as crates/shade/src/polarization.rs draws them (each output pixel takes the
// colour of the last tick that covers it, in the crate's drawing order), from the file's
// pol and dir channels and each object's axis: a new axis re-shades, never re-traces.
//
// The layers, look mode, image textures and samples per pixel are chosen when the program is
// compiled (shadeSource): software WebGL (SwiftShader) runs every branch of a shader for
// every pixel, so a program holds only the code its settings use.

export const VERTEX = `#version 300 es
// One triangle covering the viewport.
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`;

const SHADE_BODY = `
precision highp float;
precision highp int;
precision highp usampler2D;
precision highp sampler2DArray;

uniform usampler2D uId;       // 0 background, 1 failed, 2 step budget, 3 not traced, 4 + k object k
uniform sampler2D uU, uV, uG, uT;
uniform usampler2D uCos;      // round(65535 clamp(cos_i, 0, 1))
uniform sampler2DArray uLight;
uniform sampler2D uObjects;   // per object (row): moves, first texture, second texture, (T, Y(T)), polarization axis (x, y, z, on)
uniform sampler2D uPol, uDir; // pol_x, pol_y, pol_z and dir_x, dir_y, dir_z (polarization layer)
uniform int uTickStep;        // the polarization layer's grid spacing, pixels
uniform sampler2D uGt;        // g·T table, 1024 bins a row: rows [0, n) unit colour + Y, [n, 2n) normalized
uniform sampler2D uAtlas;     // image textures (linear RGB, decoded as the CPU does), stacked
uniform sampler2D uOverlay;   // the overlay layer (marks, legend, labels), RGBA, picture size

uniform float uWinLo, uWinHi;        // f32 bounds equivalent to the f64 window
uniform float uTravelLo, uTravelHi;
uniform vec3 uStops[5];              // false-colour stops, linear
uniform bool uPhysical;
uniform float uExposure, uAmbient;
uniform float uGain;                 // 2^ev: exposure compensation before the tone curve
uniform int uLights;
uniform vec3 uLightW[16];
uniform uint uGtFirst;
uniform int uGtBins, uGtRows;
uniform float uTMin, uTMax, uLnTMin, uLnStep, uNodeLast;
uniform vec3 uUnitLow, uUnitHigh;
uniform vec4 uLnY;                   // ln Y at nodes 0, 1, last, last + 1

uniform ivec2 uSize;                 // the data file's size
uniform vec2 uCamAngles;             // pinhole: tan(fov/2); panorama: h, v fov (rad); fisheye: fov/2
uniform ivec2 uOut;                  // output size
uniform vec3 uF, uR, uUp;            // camera axes, moving observer's frame
uniform vec3 uVDir;
uniform float uSpeed, uGamma;
uniform vec3 uF0, uR0, uUp0;         // the sphere's camera axes, static frame

uniform ivec4 uRef0, uRef1;          // reference squares: x0, y0, side, side (side 0: none)
uniform vec3 uRefColour0, uRefColour1; // their 8-bit sRGB / 255

out vec4 outColour;

const vec3 BACKGROUND = vec3(0.004, 0.006, 0.02);
const vec3 FAILED = vec3(1.0, 0.0, 1.0);
const vec3 STEP_BUDGET = vec3(0.15, 0.0, 0.15);
const vec3 NOT_TRACED = vec3(0.0);
const float PI = 3.141592653589793;

bool finite(float x) { return !isnan(x) && !isinf(x); }

float srgbEncode8(float x) {
  x = isnan(x) ? 0.0 : clamp(x, 0.0, 1.0);
  float s = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
  return floor(s * 255.0 + 0.5) / 255.0;
}

// The display tone curve of crates/shade/src/colour.rs (tone_map): identity up to the knee
// 0.8, then a shoulder 0.8 + 0.2·y/(1 + y), y = (x − 0.8)/0.2, that never reaches white.
float toneMap(float x) {
  if (isnan(x)) return 0.0;
  if (x <= 0.8) return x;
  if (isinf(x)) return 1.0;
  float y = (x - 0.8) / 0.2;
  return 0.8 + 0.2 * (y / (1.0 + y));
}

vec3 hue(float h) {
  vec3 k = vec3(5.0, 3.0, 1.0) + h * 6.0;
  k = mix(k, k - 6.0, step(6.0, k));
  return 1.0 - clamp(min(k, 4.0 - k), 0.0, 1.0);
}

vec3 atlasTexel(int y0, int c, int r) {
  return texelFetch(uAtlas, ivec2(c, y0 + r), 0).rgb;
}

// A texture (kind, a, b, c) at moved coordinates (u, v); crates/shade/src/texture.rs.
vec3 sampleTexture(vec4 t, float u, float v) {
  u = finite(u) ? u - floor(u) : 0.0;
  if (u >= 1.0) u = 0.0;
  v = isnan(v) ? 0.0 : clamp(v, 0.0, 1.0);
  int kind = int(t.x);
  if (kind == 0) {                     // checker: a rows, b cols
    uint rows = uint(t.y), cols = uint(t.z);
    uint i = min(uint(u * t.z), cols - 1u);
    uint j = min(uint(v * t.y), rows - 1u);
    if (((i + j) & 1u) == 0u) {
      vec3 grey = vec3(0.9);
      return grey + (hue(u) * 0.9 - grey) * 0.5;
    }
    return (u < 0.5 && v >= 0.5) ? vec3(0.35, 0.03, 0.03) : vec3(0.15);
  }
  if (kind == 1) {                     // gradient
    if (u < 0.01 || u > 0.99) return vec3(1.0);
    return vec3(u, 0.2, v);
  }
  if (kind == 2) return t.yzw;         // uniform
#if IMAGES
  // image: a = first atlas row, b = width, c = height; bilinear, wrapping in u, clamped in v
  int w = int(t.z), h = int(t.w), y0 = int(t.y);
  float x = u * t.z - 0.5;
  float y = (1.0 - v) * t.w - 0.5;
  float x0 = floor(x), yf = floor(y);
  float fx = x - x0, fy = y - yf;
  int c0 = int(x0), c1 = c0 + 1;
  c0 = c0 < 0 ? c0 + w : (c0 >= w ? c0 - w : c0);
  c1 = c1 < 0 ? c1 + w : (c1 >= w ? c1 - w : c1);
  int r0 = clamp(int(yf), 0, h - 1), r1 = clamp(int(yf) + 1, 0, h - 1);
  vec3 top = mix(atlasTexel(y0, c0, r0), atlasTexel(y0, c1, r0), fx);
  vec3 bottom = mix(atlasTexel(y0, c0, r1), atlasTexel(y0, c1, r1), fx);
  return top + (bottom - top) * fy;
#else
  return vec3(1.0, 0.0, 1.0);
#endif
}

vec4 gtEntry(int i, int part) {
  return texelFetch(uGt, ivec2(i & 1023, (i >> 10) + part * uGtRows), 0);
}

// Black body at g·T (crates/shade/src/shading.rs, blackbody), for g finite and > 0.
vec3 blackbody(float g, float temperature, float lumT) {
  float gt = g * temperature;
  vec3 unit;
  float lum;
  vec3 normalized;
  if (gt >= uTMin && gt <= uTMax) {
    int i = clamp(int((floatBitsToUint(gt) >> 13u) - uGtFirst), 0, uGtBins - 1);
    vec4 e = gtEntry(i, 0);
    unit = e.rgb;
    lum = e.a;
    normalized = gtEntry(i, 1).rgb;
  } else {
    // Outside the table: the grid's end colour, ln Y extrapolated linearly in ln T.
    float s = (log(gt) - uLnTMin) / uLnStep;
    if (gt < uTMin) {
      unit = uUnitLow;
      lum = exp(uLnY.x + s * (uLnY.y - uLnY.x));
    } else {
      unit = uUnitHigh;
      lum = exp(uLnY.z + (s - uNodeLast) * (uLnY.w - uLnY.z));
    }
    float m = max(unit.r, max(unit.g, unit.b));
    normalized = m > 0.0 ? unit / m : vec3(0.0);
  }
  if (!uPhysical) return normalized;
  vec3 rgb = unit * (uExposure * lum / lumT);
  float m = max(rgb.r, max(rgb.g, rgb.b));
  return m > 1.0 ? rgb / m : rgb;
}

vec3 falseColour(float s) {
  s = isnan(s) ? 0.0 : clamp(s, 0.0, 1.0);
  float x = s * 4.0;
  int i = min(int(floor(x)), 3);
  float f = x - float(i);
  vec3 a = uStops[0], b = uStops[1];
  if (i == 1) { a = uStops[1]; b = uStops[2]; }
  if (i == 2) { a = uStops[2]; b = uStops[3]; }
  if (i == 3) { a = uStops[3]; b = uStops[4]; }
  return a + f * (b - a);
}

// What shading reads of a record: the object id (0 background, 1 failed, 2 step budget,
// 3 not traced, 4 + k object k) and the channels the compiled layers use (the others 0:
// software WebGL fetches whatever the code names).
#define WINDOW (TIME && !TRAVEL)
#define PAINTS (TEXTURE || WINDOW || LIGHT)
#define LAMBERT ((TEXTURE || WINDOW) && !LIGHT)
struct Rec {
  uint id;
  float u, v, g, t, cosI;
};

Rec recordAt(ivec2 p) {
  Rec r = Rec(texelFetch(uId, p, 0).r, 0.0, 0.0, 0.0, 0.0, 0.0);
#if PAINTS
  r.u = texelFetch(uU, p, 0).r;
  r.v = texelFetch(uV, p, 0).r;
#endif
#if FREQUENCY
  r.g = texelFetch(uG, p, 0).r;
#endif
#if TIME
  r.t = texelFetch(uT, p, 0).r;
#endif
#if LAMBERT
  r.cosI = float(texelFetch(uCos, p, 0).r) / 65535.0;
#endif
  return r;
}

// The data pixels a sample reads and their weights (summing to 1): one pixel, or in look mode
// four sphere pixels blended bilinearly where they show one image of one object
// (crates/look/src/sample.rs).
ivec2 tapP[4];
float tapW[4];
int tapN;

void onePixel(ivec2 p) {
  tapP[0] = p;
  tapW[0] = 1.0;
  tapN = 1;
}

#if SMOOTH
// u moved by a whole turn to lie within half a turn of near.
float unwrapped(float u, float near) { return u - floor(u - near + 0.5); }

// The record the taps make: the weighted mean of their fields (u on the circle).
Rec tapRecord() {
  Rec r = recordAt(tapP[0]);
  if (tapN == 1) return r;
  float u0 = r.u;
  r.u = 0.0; r.v = 0.0; r.g = 0.0; r.t = 0.0; r.cosI = 0.0;
  for (int k = 0; k < 4; k++) {
    Rec o = recordAt(tapP[k]);
    float w = tapW[k];
    r.u += w * unwrapped(o.u, u0);
    r.v += w * o.v;
    r.g += w * o.g;
    r.t += w * o.t;
    r.cosI += w * o.cosI;
  }
  r.u -= floor(r.u);
  return r;
}
#else
Rec tapRecord() { return recordAt(tapP[0]); }
#endif

// Light plane k at the taps: the weighted mean where all are finite, else the heaviest tap's.
float tapLight(int k) {
  float x = texelFetch(uLight, ivec3(tapP[0], k), 0).r;
#if SMOOTH
  if (tapN == 4) {
    float sum = 0.0, best = -1.0, heaviest = x;
    bool all = true;
    for (int j = 0; j < 4; j++) {
      float y = texelFetch(uLight, ivec3(tapP[j], k), 0).r;
      all = all && finite(y);
      sum += tapW[j] * y;
      if (tapW[j] > best) { best = tapW[j]; heaviest = y; }
    }
    x = all ? sum : heaviest;
  }
#endif
  return x;
}

// Linear RGB of the taps' record, its frequency shift multiplied by doppler. Which layers run
// is fixed at compile time (TEXTURE, TIME, TRAVEL, FREQUENCY, LIGHT).
vec3 shadeRecord(Rec r, float doppler) {
  uint id = r.id;
  if (id < 4u) {
    return id == 0u ? BACKGROUND : id == 1u ? FAILED : id == 2u ? STEP_BUDGET : NOT_TRACED;
  }
  int o = int(id - 4u);
  vec3 c = vec3(1.0);
#if PAINTS
  vec4 move = texelFetch(uObjects, ivec2(0, o), 0);
  float u = move.x * r.u + move.z;
  float v = move.y * r.v + move.w;
  vec3 first = sampleTexture(texelFetch(uObjects, ivec2(1, o), 0), u, v);
#endif
#if TEXTURE
  c *= first;
#endif
#if TIME
  float t = r.t;
#if TRAVEL
  c *= falseColour((-t - uTravelLo) / (uTravelHi - uTravelLo));
#else
  vec3 second = sampleTexture(texelFetch(uObjects, ivec2(2, o), 0), u, v);
  c *= (t >= uWinLo && t <= uWinHi) ? second : first;
#endif
#endif
#if FREQUENCY
  vec4 body = texelFetch(uObjects, ivec2(3, o), 0);
  float g = r.g * doppler;
  if (!finite(g) || g <= 0.0) return FAILED;
  c *= blackbody(g, body.x, body.y);
#endif
#if LIGHT
#if !TEXTURE && !TIME && !FREQUENCY
  c = first;   // the light layer alone lights the first texture
#endif
  vec3 l = vec3(uAmbient);
  for (int k = 0; k < 16; k++) {
    if (k >= uLights) break;
    float x = tapLight(k);
    x = finite(x) ? max(x, 0.0) : 0.0;
    l += uLightW[k] * x;
  }
  c *= l;
#elif TEXTURE || WINDOW
  c *= 0.25 + 0.75 * r.cosI;
#endif
  return c;
}

// The taps' record as displayed, in linear light before the 8-bit encoding: hit pixels scaled
// by 2^ev and put through the tone curve, status colours (display codes) as they are;
// crates/shade/src/shading.rs and texture_shader.rs (displayed).
vec3 displayTaps(float doppler) {
  Rec r = tapRecord();
  vec3 c = shadeRecord(r, doppler);
  if (r.id < 4u || c == FAILED) return c;
  c *= uGain;
  return vec3(toneMap(c.r), toneMap(c.g), toneMap(c.b));
}

#if LOOK
// Camera-basis direction (forward, right, up) of output pixel (col, row); false where the
// camera shows nothing (crates/scene/src/camera.rs).
bool pixelDirection(vec2 centre, out vec3 d) {
  vec2 size = vec2(uOut);
#if CAMERA == 0
  float x = uCamAngles.x * (2.0 * centre.x / size.x - 1.0);
  float y = uCamAngles.x * (size.y / size.x) * (1.0 - 2.0 * centre.y / size.y);
  d = normalize(vec3(1.0, x, y));
  return true;
#elif CAMERA == 1
  float alpha = uCamAngles.x * (centre.x / size.x - 0.5);
  float beta = uCamAngles.y * (0.5 - centre.y / size.y);
  d = vec3(cos(beta) * cos(alpha), cos(beta) * sin(alpha), sin(beta));
  return true;
#else
  float dx = 2.0 * centre.x / size.x - 1.0;
  float dy = 1.0 - 2.0 * centre.y / size.y;
  float rho = length(vec2(dx, dy));
  if (rho > 1.0) return false;
  float theta = rho * uCamAngles.x;
  vec2 psi = rho > 0.0 ? vec2(dx, dy) / rho : vec2(0.0, 1.0);
  d = vec3(cos(theta), sin(theta) * psi.x, sin(theta) * psi.y);
  return true;
#endif
}
#endif

#if LOOK
// Sphere column col wrapped around, row as it is.
ivec2 wrapped(float col, float row) {
  int c = int(col) % uSize.x;
  return ivec2(c < 0 ? c + uSize.x : c, int(row));
}

// The taps of the sphere at position (x, y) (crates/look/src/sample.rs): with SMOOTH, the four
// pixels whose centres surround it where they show one image of one object (all hits of one
// object, emission times within 0.5, u on the circle and v within 0.25), else (and without
// SMOOTH, while a drag turns the view) the one it falls in.
void sphereTaps(vec2 pos) {
  onePixel(wrapped(floor(pos.x), clamp(floor(pos.y), 0.0, float(uSize.y - 1))));
#if SMOOTH
  vec2 c = pos - 0.5;
  vec2 c0 = floor(c);
  if (c0.y < 0.0 || c0.y + 1.0 > float(uSize.y - 1)) return;
  vec2 f = c - c0;
  ivec2 q[4] = ivec2[4](wrapped(c0.x, c0.y), wrapped(c0.x + 1.0, c0.y),
    wrapped(c0.x, c0.y + 1.0), wrapped(c0.x + 1.0, c0.y + 1.0));
  uint id = texelFetch(uId, q[0], 0).r;
  if (id < 4u) return;
  float u0 = texelFetch(uU, q[0], 0).r;
  vec3 lo = vec3(1e30), hi = vec3(-1e30);
  for (int k = 0; k < 4; k++) {
    if (texelFetch(uId, q[k], 0).r != id) return;
    vec3 tuv = vec3(texelFetch(uT, q[k], 0).r, unwrapped(texelFetch(uU, q[k], 0).r, u0),
      texelFetch(uV, q[k], 0).r);
    lo = min(lo, tuv);
    hi = max(hi, tuv);
  }
  vec3 spread = hi - lo;
  if (!(spread.x <= 0.5 && spread.y <= 0.25 && spread.z <= 0.25)) return;
  tapN = 4;
  for (int k = 0; k < 4; k++) tapP[k] = q[k];
  tapW[0] = (1.0 - f.x) * (1.0 - f.y);
  tapW[1] = f.x * (1.0 - f.y);
  tapW[2] = (1.0 - f.x) * f.y;
  tapW[3] = f.x * f.y;
#endif
}

// Sets the taps of the sample at picture position at (pixel corners at integers) and its
// Doppler factor; false where the camera shows nothing.
bool lookSample(vec2 at, out float doppler) {
  vec3 d;
  if (!pixelDirection(at, d)) return false;
  vec3 own = d.x * uF + d.y * uR + d.z * uUp;
  // Aberration (look crate, spacetime::aberrate): the static observer's direction n.
  float along = dot(own, uVDir);
  doppler = 1.0 / (uGamma * (1.0 - uSpeed * along));
  vec3 n = (own + ((uGamma - 1.0) * along - uGamma * uSpeed) * uVDir) * doppler;
  float alpha = atan(dot(n, uR0), dot(n, uF0));
  float beta = asin(clamp(dot(n, uUp0), -1.0, 1.0));
  float x = float(uSize.x) * (alpha / (2.0 * PI) + 0.5);
  float y = float(uSize.y) * (0.5 - beta / PI);
  sphereTaps(vec2(x, y));
  return true;
}
#endif

#if POLARIZATION
// The polarization layer (docs/physics.md, "Polarization"; crates/shade/src/polarization.rs).

// The cyclic colour map at χ (period π: the hue circle at 2χ), as 8-bit sRGB / 255
// (polarization.rs, cyclic_colour).
vec3 cyclicColour(float chi) {
  float h = mod(2.0 * chi, 2.0 * PI) / (2.0 * PI) * 6.0;
  float x = 1.0 - abs(mod(h, 2.0) - 1.0);
  int k = int(h);
  vec3 c = k == 0 ? vec3(1.0, x, 0.0) : k == 1 ? vec3(x, 1.0, 0.0) : k == 2 ? vec3(0.0, 1.0, x)
    : k == 3 ? vec3(0.0, x, 1.0) : k == 4 ? vec3(x, 0.0, 1.0) : vec3(1.0, 0.0, x);
  return floor((0.15 + 0.85 * c) * 255.0 + 0.5) / 255.0;
}

// Rust's f64::round: halves away from zero.
float roundAway(float x) { return sign(x) * floor(abs(x) + 0.5); }

// The observed angle χ in [0, π) at the sample of picture pixel "cell" (the sample nearest
// its centre), false where it shows no object with polarized light or its light runs along
// the axis: χ = atan2(ê·(pol × dir), ê·pol) (spacetime::polarization::observed_angle).
bool observedAngle(ivec2 cell, out float chi) {
  ivec2 p = cell * SUPERSAMPLE + SUPERSAMPLE / 2;
  uint id = texelFetch(uId, p, 0).r;
  if (id < 4u) return false;
  vec4 axis = texelFetch(uObjects, ivec2(4, int(id - 4u)), 0);
  if (axis.w == 0.0) return false;
  vec3 pol = texelFetch(uPol, p, 0).xyz, dir = texelFetch(uDir, p, 0).xyz;
  vec3 e = axis.xyz - dot(axis.xyz, dir) * dir;
  float len = length(e);
  if (!(len > 1e-6)) return false;
  e /= len;
  chi = atan(dot(e, cross(pol, dir)), dot(e, pol));
  if (chi < 0.0) chi += PI;
  if (chi >= PI) chi -= PI;
  return true;
}

// Pixel q under the ticks of the grid cells near it, drawn in the crate's order (rows, then
// columns; each tick's dark outline, then its colour): the colour of the last to cover q, or
// c. A tick runs 0.4 spacings either way along (sin χ, −cos χ) (y down), plotted at
// 4·0.8·spacing + 1 points as squares of half-width 1 (outline 2; 0 and 1 on grids under
// 14 pixels), so only the cells within a spacing of q can reach it.
vec3 ticks(ivec2 q, vec3 c) {
  int spacing = uTickStep;
  float half_ = 0.4 * float(spacing);
  int n = int(ceil(4.0 * half_));
  int core = spacing >= 14 ? 1 : 0;
  ivec2 first = (q - spacing / 2) / spacing;
  for (int j = first.y - 1; j <= first.y + 1; j++) {
    int cy = spacing / 2 + j * spacing;
    if (j < 0 || cy >= uOut.y) continue;
    for (int i = first.x - 1; i <= first.x + 1; i++) {
      int cx = spacing / 2 + i * spacing;
      float chi;
      if (i < 0 || cx >= uOut.x || !observedAngle(ivec2(cx, cy), chi)) continue;
      vec2 d = vec2(sin(chi), -cos(chi));
      int near = 1000000;
      for (int k = 0; k <= n; k++) {
        float t = -half_ + 2.0 * half_ * float(k) / float(n);
        ivec2 at = ivec2(roundAway(float(cx) + t * d.x), roundAway(float(cy) + t * d.y));
        ivec2 off = abs(q - at);
        near = min(near, max(off.x, off.y));
      }
      if (near <= core + 1) c = vec3(20.0 / 255.0);
      if (near <= core) c = cyclicColour(chi);
    }
  }
  return c;
}
#endif

bool inside(ivec2 q, ivec4 r) {
  return q.x >= r.x && q.y >= r.y && q.x < r.x + r.z && q.y < r.y + r.w;
}

// The reference squares, then the server's overlay layer (crates/shade/src/layer.rs)
// composited over the shaded pixel: out = layer·a + picture·(1 − a), a the layer's alpha,
// rounded to 8 bits by the RGBA8 target, as shade's layer::composite.
void main() {
  ivec2 q = ivec2(gl_FragCoord.xy);   // row 0 of the picture is texture row 0
#if LOOK
  // s×s samples at the sub-pixel points (col + (i + ½)/s, row + (j + ½)/s), as godel look
  // --samples reads them; their colours averaged as below.
  vec3 c = vec3(0.0);
  for (int j = 0; j < SUPERSAMPLE; j++) {
    for (int i = 0; i < SUPERSAMPLE; i++) {
      float doppler;
      vec2 at = vec2(q) + (vec2(i, j) + 0.5) / float(SUPERSAMPLE);
      c += lookSample(at, doppler) ? displayTaps(doppler) : NOT_TRACED;
    }
  }
  c /= float(SUPERSAMPLE * SUPERSAMPLE);
#elif SUPERSAMPLE > 1
  // An anti-aliased file: picture pixel q is the s×s block of samples from s·q; each sample
  // is coloured and tone-mapped, and the linear colours averaged (box filter,
  // crates/datafile/src/samples.rs) before the 8-bit sRGB encoding, as the shade crate does.
  vec3 c = vec3(0.0);
  for (int j = 0; j < SUPERSAMPLE; j++) {
    for (int i = 0; i < SUPERSAMPLE; i++) {
      onePixel(q * SUPERSAMPLE + ivec2(i, j));
      c += displayTaps(1.0);
    }
  }
  c /= float(SUPERSAMPLE * SUPERSAMPLE);
#else
  onePixel(q);
  vec3 c = displayTaps(1.0);
#endif
  vec4 o = vec4(srgbEncode8(c.r), srgbEncode8(c.g), srgbEncode8(c.b), 1.0);
#if POLARIZATION
  o.rgb = ticks(q, o.rgb);
#endif
#if REFS
  if (inside(q, uRef0)) o = vec4(uRefColour0, 1.0);
  if (inside(q, uRef1)) o = vec4(uRefColour1, 1.0);
#endif
#if OVERLAY
  vec4 l = texelFetch(uOverlay, q, 0);
  o.rgb = o.rgb * (1.0 - l.a) + l.rgb * l.a;
#endif
  outColour = o;
}`;

// The shading program's source for `features`: {texture, time, travel, frequency, light,
// polarization, look, smooth, images, refs, overlay} (booleans), camera (0 pinhole, 1 panorama or sphere, 2 fisheye) and
// supersample (samples per pixel along each side, 1 when absent: a sampled file's, or a
// look's).
/**
 * @param {import('./uniforms.js').Features} features
 */
export function shadeSource(features) {
  /** @type {(keyof import('./uniforms.js').Features)[]} */
  const names = ['texture', 'time', 'travel', 'frequency', 'light', 'polarization', 'look',
    'smooth', 'images', 'refs', 'overlay'];
  const defines = names.map((n) => `#define ${n.toUpperCase()} ${features[n] ? 1 : 0}`);
  defines.push(`#define CAMERA ${features.camera || 0}`);
  defines.push(`#define SUPERSAMPLE ${features.supersample || 1}`);
  return `#version 300 es\n${defines.join('\n')}\n${SHADE_BODY}`;
}

// The display pass: `filtered` samples the picture trilinearly at any zoom; otherwise it is
// copied texel for texel (zoom 1 at a whole-pixel offset, as when looking around).
/**
 * @param {boolean} filtered
 */
export function displaySource(filtered) {
  return `#version 300 es
#define FILTERED ${filtered ? 1 : 0}
precision highp float;
uniform sampler2D uShaded;
uniform vec2 uShadedSize;   // texels
uniform vec2 uCanvas;       // canvas pixels
uniform vec2 uOffset;       // canvas position of the picture's top-left corner
uniform float uZoom;        // canvas pixels per texel
out vec4 outColour;
void main() {
  vec2 canvas = vec2(gl_FragCoord.x, uCanvas.y - gl_FragCoord.y);   // from the top
  vec2 q = (canvas - uOffset) / uZoom;
  if (q.x < 0.0 || q.y < 0.0 || q.x >= uShadedSize.x || q.y >= uShadedSize.y) {
    outColour = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
#if FILTERED
  outColour = vec4(texture(uShaded, q / uShadedSize).rgb, 1.0);
#else
  outColour = vec4(texelFetch(uShaded, ivec2(q), 0).rgb, 1.0);
#endif
}`;
}
