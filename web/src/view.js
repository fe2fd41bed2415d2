// The picture, drawn by three.js as the program's renderer draws it (src/render/renderer_passes.cpp,
// shaders/): the floor's metric grid fading into the sky, the coin's planar shadow (each floor pixel
// darkened once, by the stencil), the contact trace as a ribbon coloured by age and by sliding, the
// contact marker, then the coin (brass face with blue enamel, silver back with red, knurled rim).
// Colours go to the canvas as the shaders compute them: no colour management of three's own.
import {
  BufferAttribute, BufferGeometry, ClampToEdgeWrapping, Color, ColorManagement, CustomBlending, DataTexture, DoubleSide,
  EqualStencilFunc, GLSL3, IncrementStencilOp, LinearFilter, LinearMipmapLinearFilter, LinearSRGBColorSpace, Matrix4, Mesh,
  NoColorSpace, OneFactor, OneMinusSrcAlphaFactor, PerspectiveCamera, Points, Quaternion, RepeatWrapping, Scene,
  ShaderMaterial, SrcAlphaFactor, Texture, Vector3, WebGLRenderer, WebGLRenderTarget, ZeroFactor, NearestFilter,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import faceDataUri from 'inline:face';
import { coinTriangles, kPhaseFlight, kTraceInTheAir, ribbonStrip } from './coin_geometry.js';
import { clipPlanes, upFor } from './camera_rig.js';
import { floorTile, kClassic, kFloorTileMetres } from './floor.js';

ColorManagement.enabled = false;

const kLight = new Vector3(-0.35, 1.0, 0.45).normalize();  // render/renderer_state.h kLightDirection
export const kShadowColour = [0, 0, 0, 0.45];
export const kContactColour = [0.85, 0.1, 0.08, 1];
// The coin's albedos, linear (shaders/coin.frag); the legend shows them too (legend.js).
export const kCoinColours = {
  brass: [0.80, 0.56, 0.20], silver: [0.48, 0.50, 0.55], blueEnamel: [0.03, 0.07, 0.32], redEnamel: [0.36, 0.03, 0.03],
};
const glslVec3 = (colour) => `vec3(${colour.map((c) => c.toFixed(2)).join(', ')})`;

// Blending as the renderer's: colour over colour by alpha, the canvas's alpha left alone.
const blended = { blending: CustomBlending, blendSrc: SrcAlphaFactor, blendDst: OneMinusSrcAlphaFactor,
                  blendSrcAlpha: ZeroFactor, blendDstAlpha: OneFactor };
const decal = Object.assign({ depthTest: false, depthWrite: false, side: DoubleSide }, blended);

const coinVertex = `
in float part;
out vec3 worldPosition;
out vec3 worldNormal;
out vec3 bodyPosition;
flat out int surface;
void main() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  worldPosition = world.xyz;
  worldNormal = mat3(modelMatrix) * normal;
  bodyPosition = position;
  surface = int(part + 0.5);
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

// shaders/coin.frag, with three's cameraPosition for its eye.
const coinFragment = `
out vec4 fragColour;
in vec3 worldPosition;
in vec3 worldNormal;
in vec3 bodyPosition;
flat in int surface;
uniform vec3 lightDirection;
uniform float radius;
uniform sampler2D face;
float inside(float distanceOutside) {
  float width = fwidth(distanceOutside);
  return 1.0 - smoothstep(-width, width, distanceOutside);
}
vec3 faceColour(vec3 metal, vec3 enamel) {
  vec2 p = bodyPosition.xy / radius;
  vec2 pattern = texture(face, vec2(0.5 + 0.5 * p.x, 0.5 - 0.5 * p.y)).rg;
  return mix(metal * pattern.r, enamel, pattern.g);
}
vec3 rimColour(vec3 metal) {
  float turns = atan(bodyPosition.y, bodyPosition.x) / 6.2831853;
  float stripe = abs(fract(turns * 96.0) - 0.5) - 0.25;
  return mix(metal, metal * 0.55, inside(stripe));
}
vec3 toSrgb(vec3 linear) {
  vec3 low = linear * 12.92;
  vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
  return mix(low, high, step(vec3(0.0031308), linear));
}
void main() {
  vec3 brass = ${glslVec3(kCoinColours.brass)};
  vec3 silver = ${glslVec3(kCoinColours.silver)};
  vec3 albedo;
  if (surface == 0) albedo = faceColour(brass, ${glslVec3(kCoinColours.blueEnamel)});
  else if (surface == 1) albedo = faceColour(silver, ${glslVec3(kCoinColours.redEnamel)});
  else if (surface == 2) albedo = rimColour(brass);
  else albedo = brass * 0.7;
  vec3 n = normalize(worldNormal);
  vec3 v = normalize(cameraPosition - worldPosition);
  vec3 h = normalize(lightDirection + v);
  vec3 ambient = mix(vec3(0.20, 0.19, 0.17), vec3(0.38, 0.42, 0.48), 0.5 + 0.5 * n.y);
  float diffuse = max(dot(n, lightDirection), 0.0);
  float specular = pow(max(dot(n, h), 0.0), 40.0) * step(0.0, dot(n, lightDirection));
  vec3 linear = albedo * (ambient + 0.85 * diffuse) + 0.45 * specular * mix(albedo, vec3(1.0), 0.3);
  fragColour = vec4(toSrgb(clamp(linear, 0.0, 1.0)), 1.0);
}`;

const floorVertex = `
uniform vec2 centre;
uniform float extent;
out vec3 worldPosition;
void main() {
  vec2 xz = centre + extent * position.xy;
  worldPosition = vec3(xz.x, 0.0, xz.y);
  gl_Position = projectionMatrix * viewMatrix * vec4(worldPosition, 1.0);
}`;

const floorFragment = `
out vec4 fragColour;
in vec3 worldPosition;
uniform sampler2D gridTile;
uniform float tileMetres;
uniform float fogStart;
uniform float fogEnd;
uniform vec3 backgroundSrgb;
void main() {
  vec3 floorColour = texture(gridTile, worldPosition.xz / tileMetres).rgb;
  float fog = smoothstep(fogStart, fogEnd, length(worldPosition - cameraPosition));
  fragColour = vec4(mix(floorColour, backgroundSrgb, fog), 1.0);
}`;

// The ribbon's width is a uniform (it follows the camera) and its age is the point's index over the
// newest's, so that one buffer serves every frame.
const traceVertex = `
in vec2 point;
in vec2 side;
in float index;
in float sliding;
uniform float halfWidth;
uniform float lastIndex;
out float vertexAge;
out float vertexSliding;
void main() {
  vertexAge = 1.0 - index / lastIndex;
  vertexSliding = sliding;
  vec2 p = point + halfWidth * side;
  gl_Position = projectionMatrix * viewMatrix * vec4(p.x, 0.0, p.y, 1.0);
}`;

const traceFragment = `
out vec4 fragColour;
in float vertexAge;
in float vertexSliding;
uniform vec3 recentRolling;
uniform vec3 oldRolling;
uniform vec3 recentSliding;
uniform vec3 oldSliding;
uniform vec2 opacity;
void main() {
  if (vertexSliding > 1.5) discard;  // in the air: no contact to trace
  vec3 recent = mix(recentRolling, recentSliding, vertexSliding);
  vec3 old = mix(oldRolling, oldSliding, vertexSliding);
  fragColour = vec4(mix(recent, old, vertexAge), mix(opacity.x, opacity.y, vertexAge));
}`;

// The cached sky and floor, laid over the whole picture pixel for pixel.
const backgroundVertex = 'out vec2 texel; void main() { texel = 0.5 + 0.5 * position.xy; gl_Position = vec4(position.xy, 0.0, 1.0); }';
const backgroundFragment = 'out vec4 fragColour; in vec2 texel; uniform sampler2D picture; void main() { fragColour = texture(picture, texel); }';

const flatVertex = 'uniform float pointSize; void main() { gl_PointSize = pointSize; gl_Position = projectionMatrix * viewMatrix * modelMatrix * vec4(position, 1.0); }';
const flatFragment = 'out vec4 fragColour; uniform vec4 colour; void main() { fragColour = colour; }';

const shader = (vertexShader, fragmentShader, uniforms, extra = {}) =>
  new ShaderMaterial(Object.assign({ glslVersion: GLSL3, vertexShader, fragmentShader, uniforms }, extra));
const flat = (colour, extra = {}) => shader(flatVertex, flatFragment, { colour: { value: colour }, pointSize: { value: 1 } }, extra);

// A ribbon of `points` vertex pairs as triangles: three.js draws no triangle strips.
function stripTriangles(points) {
  const index = new Uint32Array(6 * Math.max(points - 1, 0));
  for (let k = 0; k + 1 < points; ++k) index.set([2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 1, 2 * k + 3, 2 * k + 2], 6 * k);
  return index;
}

function geometry(attributes) {
  const g = new BufferGeometry();
  for (const [name, [array, size]] of Object.entries(attributes)) g.setAttribute(name, new BufferAttribute(array, size));
  return g;
}

function mesh(g, material, order) {
  const m = new Mesh(g, material);
  m.renderOrder = order;
  m.frustumCulled = false;
  return m;
}

// x' = x - (l.x / l.y) y, y' = 0, z' = z - (l.z / l.y) y: points onto the floor along the light.
const shadowProjection = new Matrix4().set(1, -kLight.x / kLight.y, 0, 0, 0, 0, 0, 0, 0, -kLight.z / kLight.y, 1, 0, 0, 0, 0, 1);

export class View {
  constructor(canvas) {
    this.renderer = new WebGLRenderer({ canvas, antialias: true, stencil: true, alpha: false });
    this.renderer.outputColorSpace = LinearSRGBColorSpace;
    this.renderer.setClearColor(new Color(...kClassic.backgroundSrgb), 1);
    this.scene = new Scene();
    this.camera = new PerspectiveCamera(35, 1, 0.01, 100);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.maxPolarAngle = 0.5 * Math.PI - 0.01;  // never under the floor, which hides what lies below
    this.userCamera = false;
    this.controls.addEventListener('start', () => { this.userCamera = true; });
    this.controls.addEventListener('change', () => { this.dirty = true; });

    const tile = new DataTexture(floorTile(512, kClassic.floor), 512, 512);
    Object.assign(tile, { wrapS: RepeatWrapping, wrapT: RepeatWrapping, generateMipmaps: true, minFilter: LinearMipmapLinearFilter,
                          magFilter: LinearFilter, colorSpace: NoColorSpace, needsUpdate: true });
    this.floor = mesh(geometry({ position: [new Float32Array([-1, -1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0, -1, 1, 0, 1, 1, 0]), 3] }),
      shader(floorVertex, floorFragment, {
        centre: { value: [0, 0] }, extent: { value: 1 }, gridTile: { value: tile }, tileMetres: { value: kFloorTileMetres },
        fogStart: { value: 1 }, fogEnd: { value: 2 }, backgroundSrgb: { value: kClassic.backgroundSrgb },
      }, { side: DoubleSide }), 0);

    const face = new Texture();
    Object.assign(face, { flipY: false, wrapS: ClampToEdgeWrapping, wrapT: ClampToEdgeWrapping, generateMipmaps: true,
                          minFilter: LinearMipmapLinearFilter, magFilter: LinearFilter, colorSpace: NoColorSpace });
    const image = new Image();
    image.onload = () => { face.image = image; face.needsUpdate = true; this.dirty = true; };
    image.src = faceDataUri;
    this.coinMaterial = shader(coinVertex, coinFragment, { lightDirection: { value: kLight }, radius: { value: 1 }, face: { value: face } });
    this.shadowMaterial = flat(kShadowColour, Object.assign({ stencilWrite: true, stencilFunc: EqualStencilFunc, stencilRef: 0,
                                                               stencilZPass: IncrementStencilOp }, decal));
    const t = kClassic.trace;
    this.traceUniforms = {
      halfWidth: { value: 0.001 }, lastIndex: { value: 1 }, recentRolling: { value: t.recentRolling }, oldRolling: { value: t.oldRolling },
      recentSliding: { value: t.recentSliding }, oldSliding: { value: t.oldSliding }, opacity: { value: t.opacity },
    };
    this.traceMaterial = shader(traceVertex, traceFragment, this.traceUniforms, decal);

    const marker = [];
    for (let i = 0; i < 32; ++i) {
      const a0 = 2 * Math.PI * i / 32, a1 = 2 * Math.PI * (i + 1) / 32;
      marker.push(0, 0, 0, Math.cos(a1), 0, Math.sin(a1), Math.cos(a0), 0, Math.sin(a0));
    }
    this.marker = mesh(geometry({ position: [new Float32Array(marker), 3] }), flat(kContactColour, decal), 3);
    // Test marks: a 5-pixel square each at the coin's centre and its contact point, over everything,
    // so that a browser test can find where the page put them (tests/web/page_test.mjs).
    this.testMarks = [[1, 0, 1, 1], [0, 1, 1, 1]].map((colour) => {
      const p = new Points(geometry({ position: [new Float32Array(3), 3] }), flat(colour, { depthTest: false, depthWrite: false }));
      p.material.uniforms.pointSize.value = 5;
      p.renderOrder = 10;
      p.frustumCulled = false;
      p.visible = false;
      return p;
    });
    // The sky and the floor are most of a frame's time in software WebGL (48 of 60 ms at 1280x720)
    // and the same while the camera stays put: drawn once per camera into a picture, which each
    // frame copies, as the renderer reuses its background (render/renderer_passes.cpp).
    this.backgroundScene = new Scene();
    this.backgroundScene.add(this.floor);
    this.backgroundQuad = mesh(this.floor.geometry, shader(backgroundVertex, backgroundFragment, { picture: { value: null } },
                                                           { depthTest: false, depthWrite: false, side: DoubleSide }), -1);
    this.scene.add(this.backgroundQuad, this.marker, ...this.testMarks);
    this.dirty = true;
  }

  // A new run: the coin's mesh for its shape, the trace's ribbon over the whole run.
  setRun(trajectory, shape, showTrace) {
    for (const old of [this.coin, this.shadow, this.trace, this.traceTail]) {
      if (old) { this.scene.remove(old); old.geometry.dispose(); }
    }
    const triangles = coinTriangles(shape);
    const coinGeometry = geometry({ position: [triangles.position, 3], normal: [triangles.normal, 3], part: [triangles.part, 1] });
    this.coinMaterial.uniforms.radius.value = shape.radius - shape.edgeRadius;
    this.coin = mesh(coinGeometry, this.coinMaterial, 4);
    this.shadow = mesh(coinGeometry, this.shadowMaterial, 1);
    this.shadow.matrixAutoUpdate = false;
    this.radius = shape.radius;
    const c = trajectory.columns;
    const ribbon = ribbonStrip(c.contact_x, c.contact_z, c.sliding, trajectory.rows, c.phase);
    this.ribbonIndex = ribbon.index;
    this.trace = mesh(geometry({ point: [ribbon.point, 2], side: [ribbon.side, 2], index: [ribbon.index, 1], sliding: [ribbon.sliding, 1] }), this.traceMaterial, 2);
    this.trace.geometry.setIndex(new BufferAttribute(stripTriangles(ribbon.vertices / 2), 1));
    this.traceTail = mesh(geometry({ point: [new Float32Array(8), 2], side: [new Float32Array(8), 2], index: [new Float32Array(4), 1],
                                     sliding: [new Float32Array(4), 1] }), this.traceMaterial, 2);
    this.traceTail.geometry.setIndex(new BufferAttribute(stripTriangles(2), 1));
    this.showTrace = showTrace;
    this.trace.visible = this.traceTail.visible = this.marker.visible = showTrace;
    this.scene.add(this.coin, this.shadow, this.trace, this.traceTail);
    this.dirty = true;
  }

  // The picture at one moment: `state` from Trajectory.stateAt, `view` {eye, target, fov} from the
  // camera rig (ignored while the user steers the camera), `trajectory` for the trace so far.
  draw(state, view, trajectory) {
    const q = new Quaternion().setFromAxisAngle(new Vector3(0, 1, 0), state.phi)
      .multiply(new Quaternion().setFromAxisAngle(new Vector3(1, 0, 0), state.theta))
      .multiply(new Quaternion().setFromAxisAngle(new Vector3(0, 0, 1), state.psi));
    this.coin.position.set(state.x, state.y, state.z);
    this.coin.quaternion.copy(q);
    this.coin.updateMatrix();
    this.shadow.matrix.multiplyMatrices(shadowProjection, this.coin.matrix);
    this.shadow.matrixWorldNeedsUpdate = true;

    const camera = this.camera;
    if (this.userCamera) {
      // A followed coin keeps the user's view of it: the view moves with the coin.
      if (view.follows && this.lastCentre) {
        const shift = new Vector3(state.x, state.y, state.z).sub(this.lastCentre);
        camera.position.add(shift);
        this.controls.target.add(shift);
      }
      this.controls.update();
    } else {
      camera.up.set(...upFor(view));
      camera.position.set(...view.eye);
      this.controls.target.set(...view.target);
      camera.lookAt(this.controls.target);
    }
    this.lastCentre = new Vector3(state.x, state.y, state.z);
    const { near, far } = clipPlanes({ eye: camera.position.toArray(), target: this.controls.target.toArray() });
    const distance = camera.position.distanceTo(this.controls.target);
    Object.assign(camera, { fov: view.fov, aspect: this.width / this.height, near, far });
    camera.updateProjectionMatrix();
    camera.updateMatrixWorld();

    const floor = this.floor.material.uniforms;
    floor.centre.value = [this.controls.target.x, this.controls.target.z];
    floor.extent.value = 150 * distance;
    floor.fogStart.value = 2.5 * distance;
    floor.fogEnd.value = 12 * distance;

    // Trace: the points strictly before t, then the contact point now (pipeline/snapshot.cpp), about
    // 2.5 pixels wide at the target and at least a twentieth of the radius.
    const traceWidth = Math.max(2.5 * 2 * distance * Math.tan(0.5 * view.fov * Math.PI / 180) / this.height, 0.05 * this.radius);
    const before = Math.min(Math.ceil(state.t / trajectory.sampleDt - 1e-9), trajectory.rows);
    this.traceUniforms.halfWidth.value = 0.5 * traceWidth;
    this.traceUniforms.lastIndex.value = Math.max(before, 1);
    this.trace.geometry.setDrawRange(0, 6 * Math.max(lowerBound(this.ribbonIndex, before, 2) - 1, 0));
    this.setTail(trajectory, before, state);
    const markerRadius = Math.max(0.08 * this.radius, 1.6 * traceWidth);
    this.marker.position.set(state.contact_x, 0, state.contact_z);
    this.marker.scale.setScalar(markerRadius);
    this.marker.visible = this.showTrace && state.phase !== kPhaseFlight;
    const [centreMark, contactMark] = this.testMarks;
    centreMark.position.set(state.x, state.y, state.z);
    contactMark.position.set(state.contact_x, 0, state.contact_z);
    const seen = [...camera.matrixWorld.elements, ...camera.projectionMatrix.elements, this.floor.visible].join();
    if (seen !== this.backgroundSeen) {
      this.renderer.setRenderTarget(this.background);
      this.renderer.render(this.backgroundScene, camera);
      this.renderer.setRenderTarget(null);
      this.backgroundSeen = seen;
    }
    this.renderer.render(this.scene, camera);
    this.dirty = false;
  }

  // The ribbon's last piece, from the newest point before t to the contact point now.
  setTail(trajectory, before, state) {
    const g = this.traceTail.geometry;
    const c = trajectory.columns;
    const from = before - 1;
    const tx = state.contact_x - (from >= 0 ? c.contact_x[from] : state.contact_x), tz = state.contact_z - (from >= 0 ? c.contact_z[from] : state.contact_z);
    const length = Math.hypot(tx, tz);
    this.traceTail.visible = this.showTrace && from >= 0 && length > 1e-7;
    if (!this.traceTail.visible) return;
    const mark = (phase, sliding) => (phase === kPhaseFlight ? kTraceInTheAir : sliding || 0);
    const ends = [[c.contact_x[from], c.contact_z[from], from, mark(c.phase && c.phase[from], c.sliding && c.sliding[from])],
                  [state.contact_x, state.contact_z, before, mark(state.phase, state.sliding)]];
    const point = g.attributes.point.array, side = g.attributes.side.array, index = g.attributes.index.array, sliding = g.attributes.sliding.array;
    ends.forEach(([x, z, i, s], k) => {
      for (let n = 0; n < 2; ++n) {
        const v = 2 * k + n, sign = n === 0 ? 1 : -1;
        point.set([x, z], 2 * v);
        side.set([-tz / length * sign, tx / length * sign], 2 * v);
        index[v] = i;
        sliding[v] = s;
      }
    });
    for (const a of Object.values(g.attributes)) a.needsUpdate = true;
  }

  setSize(width, height, pixelRatio) {
    this.width = width;
    this.height = height;
    this.renderer.setPixelRatio(pixelRatio);
    this.renderer.setSize(width, height, false);
    if (this.background) this.background.dispose();
    this.background = new WebGLRenderTarget(Math.round(width * pixelRatio), Math.round(height * pixelRatio),
                                            { samples: 4, minFilter: NearestFilter, magFilter: NearestFilter, depthBuffer: false });
    this.backgroundQuad.material.uniforms.picture.value = this.background.texture;
    this.backgroundSeen = undefined;
    this.dirty = true;
  }

  showTestMarks(on) {
    for (const m of this.testMarks) m.visible = on;
    this.dirty = true;
  }
}

// How many of the ribbon's points lie before trace point `value` (their indices rise, `stride`
// vertices per point).
function lowerBound(indices, value, stride) {
  let lo = 0, hi = indices.length / stride;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (indices[mid * stride] < value) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}
