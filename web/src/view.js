// The picture, drawn by three.js as the program's renderer draws it (src/render/renderer_passes.cpp,
// shaders/): the floor's metric grid fading into the sky, the coin's planar shadow (each floor pixel
// darkened once, by the stencil), the contact trace as a ribbon coloured by age and by sliding, the
// contact marker, then the coin (brass face with blue enamel, silver back with red, knurled rim).
// Colours go to the canvas as the shaders compute them: no colour management of three's own.
import {
  BufferAttribute, BufferGeometry, ClampToEdgeWrapping, Color, ColorManagement, CustomBlending, DataTexture, DoubleSide,
  EqualStencilFunc, GLSL3, IncrementStencilOp, LinearFilter, LinearMipmapLinearFilter, LinearSRGBColorSpace, Matrix4, Mesh,
  NoColorSpace, OneFactor, OneMinusSrcAlphaFactor, PerspectiveCamera, Points, Quaternion, RepeatWrapping, Scene,
  ShaderMaterial, SrcAlphaFactor, Texture, Vector3, Vector4, WebGLRenderer, WebGLRenderTarget, ZeroFactor, NearestFilter,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import faceDataUri from 'inline:face';
// The renderer's own fragment shaders (shaders/*.frag), compiled here as they are; the vertex shaders
// below are the page's, in three.js's names for the attributes and matrices.
import fragmentShaders from 'inline:shaders';
import { kPhaseFlight, kTraceInTheAir, ribbonStrip } from './trace_ribbon.js';

ColorManagement.enabled = false;

const kLight = new Vector3(-0.35, 1.0, 0.45).normalize();  // render/renderer_state.h kLightDirection
export const kShadowColour = [0, 0, 0, 0.45];
export const kContactColour = [0.85, 0.1, 0.08, 1];
// The coin's albedos, linear, read off shaders/coin.frag itself for the legend (legend.js): the
// metals as it declares them, the enamels as it paints each face with them.
function shaderColour(pattern) {
  const found = fragmentShaders.coin.match(pattern);
  if (!found) throw new Error(`shaders/coin.frag no longer matches ${pattern}: the legend reads its colours there`);
  return found.slice(1, 4).map(Number);
}
const vec3 = String.raw`vec3\(([\d.]+), ([\d.]+), ([\d.]+)\)`;
export const kCoinColours = {
  brass: shaderColour(new RegExp(`vec3 brass = ${vec3}`)), silver: shaderColour(new RegExp(`vec3 silver = ${vec3}`)),
  blueEnamel: shaderColour(new RegExp(`faceColour\\(brass, ${vec3}\\)`)),
  redEnamel: shaderColour(new RegExp(`faceColour\\(silver, ${vec3}\\)`)),
};
// The depth range for a camera at `distance` m from its target, as the renderer brackets it
// (render/camera.cpp clipPlanes), for the scene's camera and one the user steers alike.
const clipPlanes = (distance) => ({ near: Math.max(1e-3, 0.02 * distance), far: 200 * distance });

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

const floorVertex = `
uniform vec2 centre;
uniform float extent;
out vec3 worldPosition;
void main() {
  vec2 xz = centre + extent * position.xy;
  worldPosition = vec3(xz.x, 0.0, xz.y);
  gl_Position = projectionMatrix * viewMatrix * vec4(worldPosition, 1.0);
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

// The cached sky and floor, laid over the whole picture pixel for pixel.
const backgroundVertex = 'out vec2 texel; void main() { texel = 0.5 + 0.5 * position.xy; gl_Position = vec4(position.xy, 0.0, 1.0); }';
const backgroundFragment = 'out vec4 fragColour; in vec2 texel; uniform sampler2D picture; void main() { fragColour = texture(picture, texel); }';

const flatVertex = 'uniform float pointSize; void main() { gl_PointSize = pointSize; gl_Position = projectionMatrix * viewMatrix * modelMatrix * vec4(position, 1.0); }';

const shader = (vertexShader, fragmentShader, uniforms, extra = {}) =>
  new ShaderMaterial(Object.assign({ glslVersion: GLSL3, vertexShader, fragmentShader, uniforms }, extra));
const flat = (colour, extra = {}) => shader(flatVertex, fragmentShaders.flat, { colour: { value: colour }, pointSize: { value: 1 } }, extra);

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
    this.scene = new Scene();
    this.camera = new PerspectiveCamera(35, 1, 0.01, 100);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.maxPolarAngle = 0.5 * Math.PI - 0.01;  // never under the floor, which hides what lies below
    this.userCamera = false;
    this.controls.addEventListener('start', () => { this.userCamera = true; });
    this.controls.addEventListener('change', () => { this.dirty = true; });

    this.floor = mesh(geometry({ position: [new Float32Array([-1, -1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0, -1, 1, 0, 1, 1, 0]), 3] }),
      shader(floorVertex, fragmentShaders.floor, {
        centre: { value: [0, 0] }, extent: { value: 1 }, eye: { value: new Vector3() }, gridTile: { value: null }, tileMetres: { value: 1 },
        fogStart: { value: 1 }, fogEnd: { value: 2 }, backgroundSrgb: { value: [0, 0, 0] },
      }, { side: DoubleSide }), 0);

    const face = new Texture();
    Object.assign(face, { flipY: false, wrapS: ClampToEdgeWrapping, wrapT: ClampToEdgeWrapping, generateMipmaps: true,
                          minFilter: LinearMipmapLinearFilter, magFilter: LinearFilter, colorSpace: NoColorSpace });
    const image = new Image();
    image.onload = () => { face.image = image; face.needsUpdate = true; this.dirty = true; };
    image.src = faceDataUri;
    // A coin drawn whole (no strobe copies here): opaque and untinted.
    this.coinMaterial = shader(coinVertex, fragmentShaders.coin, {
      lightDirection: { value: kLight }, radius: { value: 1 }, face: { value: face }, eye: { value: new Vector3() },
      opacity: { value: 1 }, tint: { value: new Vector4(0, 0, 0, 0) },
    });
    this.shadowMaterial = flat(kShadowColour, Object.assign({ stencilWrite: true, stencilFunc: EqualStencilFunc, stencilRef: 0,
                                                               stencilZPass: IncrementStencilOp }, decal));
    this.traceUniforms = {
      halfWidth: { value: 0.001 }, lastIndex: { value: 1 }, recentRolling: { value: [0, 0, 0] }, oldRolling: { value: [0, 0, 0] },
      recentSliding: { value: [0, 0, 0] }, oldSliding: { value: [0, 0, 0] }, opacity: { value: [1, 1] },
    };
    this.traceMaterial = shader(traceVertex, fragmentShaders.trace, this.traceUniforms, decal);

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

  // What the renderer draws in (the core's `picture`: render/theme.cpp, render/floor_tile.cpp): the
  // sky, the floor's grid tile and the trace's colours.
  setPicture(picture) {
    this.renderer.setClearColor(new Color(...picture.backgroundSrgb), 1);
    const n = picture.tilePixels, tile = new DataTexture(picture.floorTile, n, n);
    Object.assign(tile, { wrapS: RepeatWrapping, wrapT: RepeatWrapping, generateMipmaps: true, minFilter: LinearMipmapLinearFilter,
                          magFilter: LinearFilter, colorSpace: NoColorSpace, needsUpdate: true });
    Object.assign(this.floor.material.uniforms, { gridTile: { value: tile }, tileMetres: { value: picture.tileMetres },
                                                  backgroundSrgb: { value: Array.from(picture.backgroundSrgb) } });
    for (const [name, value] of Object.entries(picture.trace)) this.traceUniforms[name].value = Array.from(value);
    this.backgroundSeen = undefined;
    this.dirty = true;
  }

  // A new run: the coin's triangles as the renderer draws them (the core's visual track), the trace's
  // ribbon over the whole run.
  setRun(trajectory, showTrace) {
    for (const old of [this.coin, this.shadow, this.trace, this.traceTail]) {
      if (old) { this.scene.remove(old); old.geometry.dispose(); }
    }
    const { coin: triangles, coinRadius, faceRadius } = trajectory.visual;
    const coinGeometry = geometry({ position: [triangles.position, 3], normal: [triangles.normal, 3], part: [triangles.part, 1] });
    this.coinMaterial.uniforms.radius.value = faceRadius;
    this.coin = mesh(coinGeometry, this.coinMaterial, 4);
    this.shadow = mesh(coinGeometry, this.shadowMaterial, 1);
    this.shadow.matrixAutoUpdate = false;
    this.radius = coinRadius;
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
      camera.up.set(...view.up);
      camera.position.set(...view.eye);
      this.controls.target.set(...view.target);
      camera.lookAt(this.controls.target);
    }
    this.lastCentre = new Vector3(state.x, state.y, state.z);
    const distance = camera.position.distanceTo(this.controls.target);
    const { near, far } = clipPlanes(distance);
    Object.assign(camera, { fov: view.fov, aspect: this.width / this.height, near, far });
    camera.updateProjectionMatrix();
    camera.updateMatrixWorld();

    const floor = this.floor.material.uniforms;
    floor.centre.value = [this.controls.target.x, this.controls.target.z];
    floor.extent.value = 150 * distance;
    floor.eye.value.copy(camera.position);
    this.coinMaterial.uniforms.eye.value.copy(camera.position);
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
