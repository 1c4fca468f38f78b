// The three.js stage the crowd stands on: renderer, sky and fog, lights with shadows, the ground
// with a metre grid (flat, or the terrain's relief drawn from the physics' own samples), and an
// orbit camera. Units are metres, y up (docs/design.md, conventions).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { TerrainGrid } from '../sim/terrain-grid';
import { TerrainMesh } from './terrain-mesh';

const SKY = 0xbfd4e6;
/** The sky's colour overhead; SKY is its colour at the horizon (and the fog's). */
const ZENITH = 0x6f9bd1;
const GROUND = 0x9aa68c;
/** Side of the square ground plane (metres); fog hides its edge. */
const GROUND_SIZE = 400;
/** Half-size of the square the sun's shadow map covers, around the camera target (metres). */
const SHADOW_EXTENT = 12;
/** Below this width / height the screen is tall, and the first view of the crowd looks down at TALL_ELEVATION (rad). */
const TALL_ASPECT = 0.8;
const TALL_ELEVATION = THREE.MathUtils.degToRad(42);

export class Stage {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private readonly sun: THREE.DirectionalLight;
  /** The sun's position relative to the point it lights (it follows the camera target). */
  private readonly sunOffset = new THREE.Vector3(-6, 12, 8);

  constructor(canvas: HTMLCanvasElement) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, powerPreference: 'high-performance' });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFShadowMap; // (r187 dropped PCFSoftShadowMap)

    this.scene.background = this.skyTexture();
    // Fog in the sky's colour dissolves the far edge of the ground into the horizon.
    this.scene.fog = new THREE.Fog(SKY, 30, 120);

    this.camera = new THREE.PerspectiveCamera(50, 1, 0.05, 400);
    this.camera.position.set(7, 4.5, 9);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.target.set(0, 0.8, 0);
    this.controls.enableDamping = true;
    this.controls.maxPolarAngle = Math.PI * 0.495; // stay above the ground
    this.controls.minDistance = 1;
    this.controls.maxDistance = 150;

    this.scene.add(new THREE.HemisphereLight(0xdfefff, 0x5a5040, 1.6));
    this.sun = new THREE.DirectionalLight(0xfff3e0, 2.4);
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.set(2048, 2048);
    const shadowCamera = this.sun.shadow.camera;
    shadowCamera.left = shadowCamera.bottom = -SHADOW_EXTENT;
    shadowCamera.right = shadowCamera.top = SHADOW_EXTENT;
    shadowCamera.near = 0.5;
    shadowCamera.far = 60;
    // Soft edges: PCF filtering over a wider kernel (a penumbra of a few centimetres).
    this.sun.shadow.radius = 3;
    this.sun.shadow.bias = -0.0005;
    this.sun.shadow.normalBias = 0.02;
    this.scene.add(this.sun, this.sun.target);

    // The ground carries a faint 1 m grid in its texture: it gives scale and makes motion over
    // the ground readable, and mipmapping fades it out with distance instead of into moiré.
    // (Line geometry such as GridHelper is unreliable here: long lines crossing the view get
    // dropped by some software rasterisers, SwiftShader among them.)
    const texture = this.groundTexture();
    this.ground = new THREE.Mesh(
      new THREE.PlaneGeometry(GROUND_SIZE, GROUND_SIZE).rotateX(-Math.PI / 2),
      new THREE.MeshStandardMaterial({ map: texture, roughness: 0.95 }),
    );
    this.ground.receiveShadow = true;
    this.scene.add(this.ground);
    // The relief's material: the same texture, its uv in metres (one grid square per metre).
    const reliefTexture = texture.clone();
    reliefTexture.repeat.set(1 / 5, 1 / 5);
    this.reliefMaterial = new THREE.MeshStandardMaterial({ map: reliefTexture, roughness: 0.95 });

    this.followTarget();
    this.watchUserZoom(canvas);
  }

  /** The flat ground: everywhere on flat terrain, beyond the relief's grid otherwise. */
  private readonly ground: THREE.Mesh;
  private readonly reliefMaterial: THREE.MeshStandardMaterial;
  private relief: TerrainMesh | null = null;
  /** The ground the stage draws (the last grid given to setTerrain). */
  terrain: TerrainGrid | null = null;

  /**
   * Draws the ground the simulation has: the plane at its height, and the relief's samples as a
   * mesh (terrain-mesh.ts). Replaces whatever ground was drawn before.
   */
  setTerrain(grid: TerrainGrid): void {
    this.terrain = grid;
    this.ground.position.y = grid.plane;
    if (this.relief) {
      this.scene.remove(this.relief.group);
      this.relief.dispose();
      this.relief = null;
    }
    if (!grid.heights) return;
    this.relief = new TerrainMesh(grid, this.reliefMaterial);
    this.relief.follow(this.controls.target);
    this.scene.add(this.relief.group);
  }

  /** Drawing-buffer pixels per CSS pixel: the device's ratio (at most 2) times the render scale. */
  private renderScale = 1;

  /**
   * Dynamic resolution: a GPU that cannot keep up (a software rasteriser, an old laptop) draws
   * fewer pixels rather than fewer frames. `scale` is relative to the device pixel ratio.
   */
  setRenderScale(scale: number): void {
    this.renderScale = Math.min(1, Math.max(0.35, scale));
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2) * this.renderScale);
    this.resize();
  }

  get scale(): number {
    return this.renderScale;
  }

  /**
   * CSS pixels on the right covered by a panel: the view's centre moves left by half of it, so
   * what the camera looks at is in the middle of the part of the canvas one can see.
   */
  rightInset = 0;
  /** The same on the left (the optimize panel, when open). */
  leftInset = 0;
  /** CSS pixels at the bottom covered by a sheet (the gait editors on a phone): the view's centre moves up by half of it. */
  bottomInset = 0;

  /** Matches the drawing buffer and projection to the canvas's CSS size. */
  resize(): void {
    const canvas = this.renderer.domElement;
    const width = canvas.clientWidth || window.innerWidth;
    const height = canvas.clientHeight || window.innerHeight;
    this.renderer.setSize(width, height, false);
    // The canvas is a window onto a view |shift| wider, offset so that its centre sits shift/2
    // to the left of the canvas's centre (right of it for a negative shift); pixels stay
    // square: the aspect is the wider view's.
    const clamp = (inset: number) => Math.max(0, Math.min(inset, width / 3));
    const shift = clamp(this.rightInset) - clamp(this.leftInset);
    const wider = Math.abs(shift);
    // The same vertically: a view `taller` higher, extended upwards (the canvas its lower part),
    // so that its centre sits taller/2 above the canvas's, in the middle of what the sheet leaves.
    const taller = Math.max(0, Math.min(this.bottomInset, height / 2));
    this.camera.aspect = (width + wider) / Math.max(1, height + taller);
    if (wider > 0 || taller > 0) this.camera.setViewOffset(width + wider, height + taller, Math.max(0, shift), taller, width, height);
    else this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
  }

  /** Points the camera at a region: `center` seen from a distance that fits `radius`. */
  frame(center: THREE.Vector3, radius: number): void {
    const direction = this.camera.position.clone().sub(this.controls.target).normalize();
    // A tall screen (a phone held upright) fits the crowd by its width, which leaves most of its
    // height to the sky and the foreground at the usual low view: it looks down more steeply
    // instead, so that the ground around the crowd fills that height.
    if (this.camera.aspect < TALL_ASPECT && direction.y < Math.sin(TALL_ELEVATION)) {
      const level = Math.hypot(direction.x, direction.z);
      direction.set((direction.x / level) * Math.cos(TALL_ELEVATION), Math.sin(TALL_ELEVATION), (direction.z / level) * Math.cos(TALL_ELEVATION));
    }
    const fov = THREE.MathUtils.degToRad(this.camera.fov);
    const distance = Math.max(4, radius / Math.sin(fov / 2));
    this.controls.target.copy(center);
    this.camera.position.copy(center).addScaledVector(direction, distance);
    this.controls.update();
    // Widen the shadow map to the whole region (at the cost of resolution) if it is large.
    const extent = Math.max(SHADOW_EXTENT, radius * 1.3);
    const shadowCamera = this.sun.shadow.camera;
    shadowCamera.left = shadowCamera.bottom = -extent;
    shadowCamera.right = shadowCamera.top = extent;
    shadowCamera.updateProjectionMatrix();
  }

  /** Puts the camera at `from`, looking at `to`. */
  view(from: THREE.Vector3, to: THREE.Vector3): void {
    // A distance chosen, as the user's own zoom is: kept from then on (keepInView would back off to
    // hold the whole crowd, which a fast character followed for a filmstrip has left far behind).
    this.autoZoom = false;
    this.controls.target.copy(to);
    this.camera.position.copy(from);
    this.controls.update();
  }

  /**
   * Follow mode: moves the camera with a point (the selected character), keeping the view's
   * direction and distance, eased so that the character's own sway does not shake the view.
   */
  follow(point: THREE.Vector3, dt: number): void {
    const goal = new THREE.Vector3(point.x, Math.max(0.6, point.y), point.z);
    const delta = goal.sub(this.controls.target).multiplyScalar(1 - Math.exp(-dt * 4));
    this.controls.target.add(delta);
    this.camera.position.add(delta);
  }

  /**
   * Keeps a region in view, eased (the crowd wanders: its centre and size change slowly): the
   * camera's target moves towards `center` and, unless the user chose a zoom of their own, its
   * distance towards one that fits `radius`. The view's direction stays the user's.
   */
  keepInView(center: THREE.Vector3, radius: number, dt: number, followsSelection = false): void {
    const ease = 1 - Math.exp(-dt * 1.5);
    const target = this.controls.target;
    if (!followsSelection) {
      const delta = center.clone().sub(target).multiplyScalar(ease);
      target.add(delta);
      this.camera.position.add(delta);
    }
    if (!this.autoZoom) return;
    const offset = this.camera.position.clone().sub(target);
    const fov = THREE.MathUtils.degToRad(this.camera.fov);
    // The narrower of the two view angles must hold the region (a phone is tall and narrow),
    // seen from the region's middle or, following a character, from that character.
    const half = Math.min(fov / 2, Math.atan(Math.tan(fov / 2) * Math.min(1, this.camera.aspect)));
    const reach = followsSelection ? radius + center.distanceTo(target) : radius;
    const wanted = Math.min(this.controls.maxDistance, Math.max(4, (reach * 1.1) / Math.sin(half)));
    const distance = offset.length();
    offset.multiplyScalar((distance + (wanted - distance) * ease) / distance);
    this.camera.position.copy(target).add(offset);
    const extent = Math.max(SHADOW_EXTENT, Math.min(60, radius * 1.3));
    const shadowCamera = this.sun.shadow.camera;
    if (shadowCamera.right !== extent) {
      shadowCamera.left = shadowCamera.bottom = -extent;
      shadowCamera.right = shadowCamera.top = extent;
      shadowCamera.updateProjectionMatrix();
    }
  }

  /**
   * The camera's distance follows the crowd (keepInView) until the user zooms (wheel, pinch):
   * their zoom is kept from then on; a new scene or the panel's "frame the crowd" gives it back.
   */
  autoZoom = true;

  private watchUserZoom(canvas: HTMLCanvasElement): void {
    // Wheel and pinch are the zoom gestures (a one-finger or mouse drag orbits).
    canvas.addEventListener('wheel', () => (this.autoZoom = false), { passive: true });
    canvas.addEventListener('touchmove', (event) => {
      if (event.touches.length >= 2) this.autoZoom = false;
    }, { passive: true });
  }

  render(): void {
    this.controls.update();
    this.followTarget();
    this.relief?.follow(this.controls.target);
    this.renderer.render(this.scene, this.camera);
  }

  /**
   * Five metres of ground: its colour with a faint line every metre and a stronger one every
   * five, tiled over the plane (a scale one can read at a glance: a biped is 1.8 m tall).
   */
  private groundTexture(): THREE.Texture {
    const metre = 96;
    const size = 5 * metre;
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = size;
    const ctx = canvas.getContext('2d');
    if (!ctx) throw new Error('no 2D canvas context for the ground texture');
    ctx.fillStyle = `#${new THREE.Color(GROUND).getHexString()}`;
    ctx.fillRect(0, 0, size, size);
    ctx.fillStyle = 'rgba(40, 48, 34, 0.18)';
    for (let i = 1; i < 5; i++) {
      ctx.fillRect(0, i * metre, size, 2);
      ctx.fillRect(i * metre, 0, 2, size);
    }
    ctx.fillStyle = 'rgba(40, 48, 34, 0.34)';
    ctx.fillRect(0, 0, size, 4);
    ctx.fillRect(0, 0, 4, size);
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
    texture.repeat.set(GROUND_SIZE / 5, GROUND_SIZE / 5);
    // Lines stay crisp at grazing angles, where the ground is seen most.
    texture.anisotropy = this.renderer.capabilities.getMaxAnisotropy();
    return texture;
  }

  /** A sky: the horizon's colour (the fog's) rising to a deeper blue overhead. */
  private skyTexture(): THREE.Texture {
    const canvas = document.createElement('canvas');
    canvas.width = 2;
    canvas.height = 256;
    const ctx = canvas.getContext('2d');
    if (!ctx) throw new Error('no 2D canvas context for the sky');
    const gradient = ctx.createLinearGradient(0, 0, 0, 256);
    gradient.addColorStop(0, `#${new THREE.Color(ZENITH).getHexString()}`);
    gradient.addColorStop(0.5, `#${new THREE.Color(SKY).getHexString()}`);
    gradient.addColorStop(1, `#${new THREE.Color(SKY).getHexString()}`);
    ctx.fillStyle = gradient;
    ctx.fillRect(0, 0, 2, 256);
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    // An equirectangular map: its middle row is the horizon, its top the zenith.
    texture.mapping = THREE.EquirectangularReflectionMapping;
    return texture;
  }

  /**
   * The wandering crowd's arena (native/src/sim/wander.h): a faint ring on the ground at its
   * edge, or nothing (null: wandering is off).
   */
  setArena(radius: number | null): void {
    if (radius === null) {
      if (this.arena) this.arena.visible = false;
      return;
    }
    if (!this.arena) {
      this.arena = new THREE.Mesh(
        new THREE.RingGeometry(0.985, 1, 128).rotateX(-Math.PI / 2),
        new THREE.MeshBasicMaterial({ color: 0xffffff, transparent: true, opacity: 0.45, depthWrite: false }),
      );
      this.arena.renderOrder = 1;
      this.scene.add(this.arena);
    }
    this.arena.visible = true;
    this.arena.scale.set(radius, 1, radius);
    this.arena.position.y = (this.terrain?.plane ?? 0) + 0.012;
  }

  private arena: THREE.Mesh | null = null;

  /** Keeps the shadow-casting area centred where the camera looks. */
  private followTarget(): void {
    this.sun.target.position.copy(this.controls.target);
    this.sun.position.copy(this.controls.target).add(this.sunOffset);
  }
}
