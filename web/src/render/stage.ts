// The three.js stage the crowd stands on: renderer, sky and fog, lights with shadows, the ground
// with a metre grid (flat, or the terrain's relief drawn from the physics' own samples), and an
// orbit camera. Units are metres, y up (docs/design.md, conventions).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { TerrainGrid } from '../sim/terrain-grid';
import { TerrainMesh } from './terrain-mesh';

const SKY = 0xbfd4e6;
const GROUND = 0x9aa68c;
/** Side of the square ground plane (metres); fog hides its edge. */
const GROUND_SIZE = 400;
/** Half-size of the square the sun's shadow map covers, around the camera target (metres). */
const SHADOW_EXTENT = 12;

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

    this.scene.background = new THREE.Color(SKY);
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
    reliefTexture.repeat.set(1, 1);
    this.reliefMaterial = new THREE.MeshStandardMaterial({ map: reliefTexture, roughness: 0.95 });

    this.followTarget();
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
    this.camera.aspect = (width + wider) / Math.max(1, height);
    if (wider > 0) this.camera.setViewOffset(width + wider, height, Math.max(0, shift), 0, width, height);
    else this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
  }

  /** Points the camera at a region: `center` seen from a distance that fits `radius`. */
  frame(center: THREE.Vector3, radius: number): void {
    const direction = this.camera.position.clone().sub(this.controls.target).normalize();
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

  render(): void {
    this.controls.update();
    this.followTarget();
    this.relief?.follow(this.controls.target);
    this.renderer.render(this.scene, this.camera);
  }

  /** One metre of ground: its colour with a darker line along two edges, tiled over the plane. */
  private groundTexture(): THREE.Texture {
    const size = 128;
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = size;
    const ctx = canvas.getContext('2d');
    if (!ctx) throw new Error('no 2D canvas context for the ground texture');
    ctx.fillStyle = `#${new THREE.Color(GROUND).getHexString()}`;
    ctx.fillRect(0, 0, size, size);
    ctx.fillStyle = 'rgba(40, 48, 34, 0.22)';
    ctx.fillRect(0, 0, size, 2);
    ctx.fillRect(0, 0, 2, size);
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
    texture.repeat.set(GROUND_SIZE, GROUND_SIZE);
    // Lines stay crisp at grazing angles, where the ground is seen most.
    texture.anisotropy = this.renderer.capabilities.getMaxAnisotropy();
    return texture;
  }

  /** Keeps the shadow-casting area centred where the camera looks. */
  private followTarget(): void {
    this.sun.target.position.copy(this.controls.target);
    this.sun.position.copy(this.controls.target).add(this.sunOffset);
  }
}
