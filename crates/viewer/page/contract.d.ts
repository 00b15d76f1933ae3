// The viewer server's JSON, as the page reads and sends it: every answer and body of the
// routes the page calls (crates/viewer/src/*_routes.rs), typed once. The page's modules
// import these types in their JSDoc (`import('./contract').Info`); the page does not load
// this file (types only).
//
// Checked against the server: crates/viewer/tests/integration/contract.rs sends real
// requests, checks each answer against its type here (every field declared, none missing,
// each of its type) and each body built to a type here is accepted; every field declared
// here must be seen there. So this file is written in the small part of TypeScript that test
// reads: `export interface` with one `name: type;` or `name?: type;` a line, `export type`
// aliases, and the types number, string, boolean, null, 'literals', true, false, T[],
// [tuples], (parentheses), unions and Record<string, T>.

/** A 3-vector (directions, colours). */
export type Vec3 = [number, number, number];

/** Every refusal (4xx, 5xx) of an /api route: its message names the field. */
export interface ApiError {
  error: string;
}

// ---- the data file: GET /api/info, GET /api/pixel (crates/viewer/src/state.rs)

/** `GET /api/info`: what the page builds its controls from. */
export interface Info {
  file: string;
  scene_name: string;
  width: number;
  height: number;
  supersample: number;
  objects: string[];
  lights: number;
  polarization: boolean;
  observer_time: number;
  defaults: ShadeSettings;
  stereo: StereoInfo | null;
}

/** A stereo layout: the pair's pictures side by side, one over the other, or an anaglyph. */
export type StereoLayout = 'side-by-side' | 'over-under' | 'anaglyph';

/** `Info.stereo`: the file is this eye of a stereo pair in this layout; `partner` whether
 * the other eye's file is beside it (then `POST /api/stereo/png?layout=L`, settings as the
 * body, answers both eyes' picture as a PNG). */
export interface StereoInfo {
  eye: 'left' | 'right';
  layout: StereoLayout;
  partner: boolean;
}

/** A record's status, as the server names it. */
export type RayStatusName = 'hit' | 'escaped' | 'step budget' | 'failed' | 'not traced' | 'work limit';

/** `GET /api/pixel?col=C&row=R`: one pixel's record (null: a miss's meaningless numbers). */
export interface PixelRecord {
  col: number;
  row: number;
  object: number;
  object_name: string | null;
  status: RayStatusName;
  u: number | null;
  v: number | null;
  g: number | null;
  t_emit: number | null;
  travel_time: number | null;
  x: number | null;
  y: number | null;
  z: number | null;
  lights: (number | null)[];
  azimuth_deg: number | null;
  elevation_deg: number | null;
}

// ---- the shading settings: the `shade` crate's ShadeSettings (crates/shade/src/settings.rs),
// sent back as the body of /api/png, /api/stereo/png, /api/overlay, /api/keyframe and in the look routes'

export type ShaderKind = 'texture' | 'frequency' | 'time' | 'light' | 'polarization';

export interface ShadeSettings {
  shaders: ShaderKind[];
  brightness: 'normalized' | 'physical';
  exposure: number;
  reference_squares: boolean;
  ev: number;
  grid: boolean;
  time: TimeSettings;
  light: LightSettings;
  objects: Record<string, ObjectSettings>;
}

export interface TimeSettings {
  mode: 'window' | 'travel';
  t0: number;
  dt: number;
  travel_min: number;
  travel_max: number;
  legend: boolean;
}

export interface LightSettings {
  ambient: number;
  sources: LightSource[];
}

export interface LightSource {
  on: boolean;
  intensity: number;
  color: Vec3;
}

export interface ObjectSettings {
  texture: TextureChoice;
  window_texture: TextureChoice;
  offset_u: number;
  offset_v: number;
  scale_u: number;
  scale_v: number;
  rotation_deg: number;
  temperature: number;
  lamps: Lamp[];
  polarization: Vec3 | null;
}

export interface Lamp {
  u: number;
  v: number;
  radius_deg: number;
  period: number;
  phase: number;
  duty: number;
  color: Vec3;
}

/** A texture the settings choose (shade::TextureChoice). */
export type TextureChoice = SceneTexture | CheckerTexture | GradientTexture | UniformTexture
  | ImageFileTexture | EarthTexture;

/** The object's own texture in its scene (`GET /api/gpu/textures` says which). */
export interface SceneTexture {
  kind: 'scene';
}

export interface CheckerTexture {
  kind: 'checker';
  rows: number;
  cols: number;
}

export interface GradientTexture {
  kind: 'gradient';
}

export interface UniformTexture {
  kind: 'uniform';
  color: Vec3;
}

/** An image file in the data file's folder or a `--textures` folder. */
export interface ImageFileTexture {
  kind: 'image';
  path: string;
}

export interface EarthTexture {
  kind: 'earth';
}

// ---- what the page shades from (crates/viewer/src/gpu_routes.rs, gpu.rs)

/** `GET /api/gpu/textures`: each object's scene texture. */
export interface SceneTextures {
  objects: GpuTexture[];
}

/** A scene texture as the page's shader draws it (viewer::gpu::GpuTexture). */
export type GpuTexture = CheckerTexture | GradientTexture | UniformTexture | GpuImageTexture;

/** An image the page fetches from `/api/gpu/image/NAME`. */
export interface GpuImageTexture {
  kind: 'image';
  image: string;
  width: number;
  height: number;
}

/** `GET /api/gpu/blackbody`: the black-body tables (viewer::gpu::Blackbody). */
export interface Blackbody {
  t_min: number;
  t_max: number;
  gt_shift: number;
  gt_first_bin: number;
  gt_bins: number;
  ln_t_min: number;
  step: number;
  unit: Vec3[];
  ln_y: number[];
}

// ---- looking around: GET /api/view, POST /api/look/* (crates/viewer/src/look_routes.rs)

/** A camera (scene::Camera): the scene file's `[camera]` table without `samples`. */
export type Camera = PinholeCamera | PanoramaCamera | SphereCamera | FisheyeCamera;

export interface PinholeCamera {
  kind: 'pinhole';
  fov_deg: number;
  width: number;
  height: number;
}

export interface PanoramaCamera {
  kind: 'panorama';
  h_fov_deg: number;
  v_fov_deg: number;
  width: number;
  height: number;
}

export interface SphereCamera {
  kind: 'sphere';
  width: number;
  height: number;
}

/** A fisheye's width and height are equal. */
export interface FisheyeCamera {
  kind: 'fisheye';
  fov_deg: number;
  width: number;
  height: number;
}

/** The observer's velocity relative to the static observer. */
export interface Velocity {
  speed: number;
  direction: Vec3;
}

/** A view to look at (look_routes::ViewJson): the axes in the moving observer's frame. */
export interface LookView {
  camera: Camera;
  forward: Vec3;
  up: Vec3;
  velocity: Velocity;
  samples: number;
}

/** `GET /api/view`: the file's own view, and whether the page can look around in it. */
export interface ViewInfo {
  view: LookView | null;
  sphere: boolean;
  sphere_error: string | null;
  object_directions: (Vec3 | null)[];
}

/** The body of `POST /api/look/png`, `/api/look/image` and `/api/look/overlay`. */
export interface LookRequest {
  settings: ShadeSettings;
  view: LookView;
}

// ---- the GPU kernel's input: GET /api/gpu/input (crates/viewer/src/kernel_routes.rs)

/** `GET /api/gpu/input`: what the kernel reads (kernel_routes::PageInput). */
export interface KernelInput {
  uniforms: KernelUniforms;
  table: number[];
  table_rows: number;
  objects: number;
  light_count: number;
  kinds: [boolean, boolean, boolean, boolean];
  supersample: number;
  /** A Gödel-type member's constants (the defines say whether it is causal); null otherwise. */
  member: MemberConstants | null;
  slots: number;
  light_channels: [number, number][];
  draw_buffers: number;
  defines: string;
  plan: RoundPlan;
  phase_done: number;
  first_budget: number;
  max_rounds: number;
}

/** gpu::input::MemberConstants. */
export interface MemberConstants {
  m2: number;
  omega: number;
  delta: number;
  causal: boolean;
  step: number;
}

/** gpu::input::Uniforms, its observer's (ObserverUniforms) at the top level. */
export interface KernelUniforms {
  /** 0 Minkowski, 1 Gödel, 2 a Gödel-type member. */
  metric: number;
  a: number;
  obs_t: [number, number];
  obs_x: Vec3;
  obs_static: number[];
  obs_to: [number, number, number, number];
  velocity: [number, number, number, number];
  forward: Vec3;
  up: Vec3;
  camera: number;
  fov: [number, number];
  size: [number, number];
  max_past: number;
  max_loops: number;
  lights: number;
  /** u_member: m², Ω, Ω² − m²/4, the longest segment; zeros outside the family. */
  member: [number, number, number, number];
}

/** What depends on the observer's position alone (gpu::input::ObserverUniforms). */
export interface ObserverUniforms {
  obs_static: number[];
  obs_to: [number, number, number, number];
}

/** How the rounds' draws write the slots (gpu::input::RoundPlan). */
export interface RoundPlan {
  rounds: Span;
  finish: Span | null;
  layers: number;
}

/** A range of layers, `start` included, `end` not. */
export interface Span {
  start: number;
  end: number;
}

// ---- explore mode (crates/viewer/src/explore_routes.rs)

/** `GET /api/explore/info`. */
export type ExploreInfo = NotExploring | Exploring;

/** `godel view`. */
export interface NotExploring {
  explore: false;
}

export interface Exploring {
  explore: true;
  start: ObserverEvent;
  bound: number;
  generation: number;
}

/** An event of the observer. */
export interface ObserverEvent {
  t: number;
  x: number;
  y: number;
  z: number;
}

/** The body of `POST /api/explore/event`. */
export interface EventRequest {
  t: number;
  x: number;
  y: number;
  z: number;
  refine: boolean;
}

/** The answer of `POST /api/explore/event`. */
export interface EventAnswer {
  generation: number;
}

/** `POST /api/explore/view-frame?wait=true`: also what `GET /api/explore/frame?after=N` answers. */
export interface ViewFrameAnswer {
  generation: number;
  answer: FrameAnswer;
}

export type Level = 'coarse' | 'full';

/** `GET /api/explore/frame`. */
export interface FrameAnswer {
  frame: FrameInfo | null;
  generation: number;
  error: string | null;
  /** Rays a millisecond of the server's last frame traced (null before any). */
  cpu_rays_per_ms: number | null;
}

export interface FrameInfo {
  generation: number;
  level: Level;
  event: ObserverEvent;
  width: number;
  height: number;
  supersample: number;
  /** The wall-clock time its trace took on the server, ms. */
  trace_ms: number;
}

/** An event on the map, with its distance r from the observer's axis (render::map). */
export interface MapPoint {
  t: number;
  x: number;
  y: number;
  z: number;
  r: number;
}

/**
 * `GET /api/explore/map` (render::map::Map). `horizon_radius` is 2a in Gödel's universe and
 * ρ_c in a Gödel-type member (closed timelike curves beyond); `member` only in a member.
 */
export interface ExploreMap {
  a: number | null;
  event: MapPoint;
  horizon_radius: number | null;
  horizon: [number, number][];
  time_range: [number, number];
  objects: MapObject[];
  member?: MemberMap;
}

/** A Gödel-type member on the map (render::map::MemberMap): `unit` is its length scale. */
export interface MemberMap {
  m2: number;
  omega: number;
  unit: number;
}

export interface MapObject {
  index: number;
  name: string;
  radius: number;
  moving: boolean;
  at: MapPoint | null;
  track: MapPoint[];
}

/** `GET /api/explore/ray`: a pixel's light ray, from the observer into the past. */
export interface LightRay {
  col: number;
  row: number;
  status: RayStatusName;
  object: number | null;
  points: MapPoint[];
  emission: MapPoint | null;
  travel_time: number | null;
}

// ---- flying: the view, its moves and checks (crates/viewer/src/view.rs, page_check.rs)

/** A pseudo-Cartesian position. */
export interface Position {
  x: number;
  y: number;
  z: number;
}

export type CameraKind = 'pinhole' | 'panorama' | 'sphere' | 'fisheye';

/** A view's camera (viewer::view::CameraView): the fields of view its kind has. */
export interface CameraView {
  kind: CameraKind;
  fov_deg?: number;
  h_fov_deg?: number;
  v_fov_deg?: number;
  width: number;
  height: number;
  samples: number;
}

/** A view: the scene file's `[observer]` and `[camera]` fields (viewer::view::View). */
export interface View {
  time: number;
  position: Position;
  velocity: Velocity;
  forward: Vec3;
  up: Vec3;
  camera: CameraView;
}

/** The body of `POST /api/explore/move`. */
export interface MoveRequest {
  time: number;
  position: Position;
  velocity: Velocity;
  tau: number;
}

/** The answer of `POST /api/explore/move`. */
export interface MoveAnswer {
  time: number;
  position: Position;
  velocity: Velocity;
  observer: ObserverUniforms;
}

/** A sample the page traced, for the server to trace again. */
export interface CheckSample {
  x: number;
  y: number;
  status: RayStatusName;
  object: number;
}

/** The body of `POST /api/explore/check`. */
export interface CheckRequest {
  view: View;
  renderer: string;
  samples: CheckSample[];
}

/** The answer of `POST /api/explore/check`. */
export interface CheckAnswer {
  verdict: 'agree' | 'disagree' | 'unchecked';
  checked: number;
  reason: string | null;
}

// ---- keeping a flight (crates/viewer/src/keep_routes.rs)

/** `GET /api/explore/view`: the scene's own view and the bounds of a recording. */
export interface OwnView {
  view: View;
  max_keyframes: number;
  record_fps: number;
}

/** The answer of `POST /api/explore/exact` (its body: a View). */
export interface ExactStarted {
  job: number;
}

export type JobState = 'rendering' | 'done' | 'failed' | 'cancelled';

/** `GET /api/explore/exact`: the newest exact render. */
export interface ExactStatus {
  job: ExactJob | null;
}

export interface ExactJob {
  id: number;
  state: JobState;
  done: number;
  total: number;
  seconds: number | null;
  error: string | null;
  summary: string | null;
  png: string | null;
  exr: string | null;
}

/** The answer of `POST /api/explore/exact/cancel`. */
export interface ExactCancelled {
  cancelled: number | null;
}

/** The body of `POST /api/explore/record`. */
export interface RecordRequest {
  keyframes: RecordedView[];
}

export interface RecordedView {
  seconds: number;
  view: View;
}
