// Where the page's camera is, by the renderer's rule (src/pipeline/camera_rig.cpp, render/camera.cpp):
// render.camera's eye and target where the scene gives them, else framed from the box of every
// centre and contact point of the run (the survey), 20 degrees round from the coin's initial face at
// the scene's elevation; `orbit` circles once per orbit_period, `follow` keeps eye - target to the coin.

const kDefaultAzimuthDegrees = 20;
const radians = (degrees) => degrees * Math.PI / 180;
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => scale(a, 1 / Math.hypot(...a));

const viewDirection = (azimuth, elevation) =>
  [Math.sin(azimuth) * Math.cos(elevation), Math.sin(elevation), Math.cos(azimuth) * Math.cos(elevation)];

// The smallest distance along towardsEye at which the box's corners fit the field of view, with 6 %.
function fittingDistance(lower, upper, target, towardsEye, tanHalfX, tanHalfY) {
  const right = normalize(cross([0, 1, 0], towardsEye));
  const up = cross(towardsEye, right);
  let distance = 0;
  for (let corner = 0; corner < 8; ++corner) {
    const p = [corner & 1 ? upper[0] : lower[0], corner & 2 ? upper[1] : lower[1], corner & 4 ? upper[2] : lower[2]];
    const q = sub(p, target);
    const towards = dot(q, towardsEye);
    distance = Math.max(distance, Math.abs(dot(q, right)) / tanHalfX + towards, Math.abs(dot(q, up)) / tanHalfY + towards);
  }
  return 1.06 * distance;
}

// spec: the scene's render.camera with the schema's defaults filled in ({mode, eye, target, fov,
// orbit_period, elevation}) and `aspect`, render.width / render.height; survey: {lower, upper};
// radius: the coin's, m; width, height: the view's pixels.
export class CameraRig {
  constructor(spec, survey, radius, width, height) {
    this.spec = spec;
    // fov is vertical: a view narrower than the program's picture (a phone held upright) would cut the
    // sides off a camera the scene places, so its field widens until the picture's width fits. A
    // framed camera fits the run to the view's own shape below.
    const narrowing = spec.aspect / (width / height);
    this.fov = spec.eye && narrowing > 1 ? 2 * Math.atan(Math.tan(0.5 * radians(spec.fov)) * narrowing) * 180 / Math.PI
      : spec.fov;
    const lower = [survey.lower[0] - radius, 0, survey.lower[2] - radius];
    const upper = [survey.upper[0] + radius, Math.max(survey.upper[1], radius) + 0.2 * radius, survey.upper[2] + radius];
    this.target = spec.target ? spec.target.slice() : scale(add(lower, upper), 0.5);
    const tanHalfY = Math.tan(0.5 * radians(spec.fov));
    const tanHalfX = tanHalfY * width / height;
    const elevation = radians(spec.elevation);
    const azimuths = spec.mode === 'orbit' ? 16 : 1;
    this.distance = 0;
    for (let i = 0; i < azimuths; ++i) {
      const azimuth = radians(kDefaultAzimuthDegrees) + 2 * Math.PI * i / azimuths;
      this.distance = Math.max(this.distance, fittingDistance(lower, upper, this.target, viewDirection(azimuth, elevation), tanHalfX, tanHalfY));
    }
    this.distance = Math.max(this.distance, 2.5 * radius / tanHalfY);
    this.followDistance = 4 * radius / Math.min(tanHalfX, tanHalfY);
  }

  // {eye, target, fov} at simulated time t with the coin's centre at `centre`.
  at(time, centre) {
    const spec = this.spec;
    const elevation = radians(spec.elevation), azimuth = radians(kDefaultAzimuthDegrees);
    if (spec.mode === 'follow') {
      const offset = spec.eye && spec.target ? sub(spec.eye, spec.target) : scale(viewDirection(azimuth, elevation), this.followDistance);
      return { eye: add(centre, offset), target: centre.slice(), fov: this.fov };
    }
    if (spec.mode === 'orbit') {
      const turn = 2 * Math.PI * time / spec.orbit_period;
      let radius = this.distance * Math.cos(elevation), height = this.distance * Math.sin(elevation), start = azimuth;
      if (spec.eye) {
        const d = sub(spec.eye, this.target);
        radius = Math.hypot(d[0], d[2]);
        height = d[1];
        start = Math.atan2(d[0], d[2]);
      }
      const eye = add(this.target, [radius * Math.sin(start + turn), height, radius * Math.cos(start + turn)]);
      return { eye, target: this.target.slice(), fov: this.fov };
    }
    const eye = spec.eye ? spec.eye.slice() : add(this.target, scale(viewDirection(azimuth, elevation), this.distance));
    return { eye, target: this.target.slice(), fov: this.fov };
  }
}

// Near and far planes as the renderer sets them (render/camera.cpp cameraMatrices), and its "up":
// looking straight down, -z.
export function clipPlanes(view) {
  const distance = Math.hypot(...sub(view.eye, view.target));
  return { near: Math.max(1e-3, 0.02 * distance), far: 200 * distance };
}
export function upFor(view) {
  const forward = normalize(sub(view.target, view.eye));
  return Math.abs(forward[1]) > 0.999 ? [0, 0, -1] : [0, 1, 0];
}
