// The 3D view: occupied voxels, the vehicle with its camera frustum, the flown path coloured by
// speed, committed trajectories coloured by mode, the local target, the goal, the sensing ray and
// the planners' debug layer. reset() empties it (a jump of mmh-viewer --log's time slider).
// Orbit camera (drag, wheel) or follow-the-vehicle mode. World frame, z up, metres.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { AWARENESS_COLORS, modeColor, speedColor } from "./colors.js";
import { DebugLayer } from "./debug_layer.js";
import { VoxelLayer } from "./voxel_layer.js";

const MAX_PATH_POINTS = 20000;
const KEPT_TRAJECTORIES = 40; // earlier commits stay, faded
const MAX_SPEED_MPS = 3.0; // top of the path's colour scale (vehicle.max_vel_mps)

export class Scene3D {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color("#f4f6f8");
    this.camera = new THREE.PerspectiveCamera(55, 1, 0.1, 500);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(-28, -22, 18);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(-10, 0, 1);
    this.controls.enableDamping = true;
    this.follow = false;
    this.framed = false; // the camera frames start and goal once, unless the user moved it first
    this.controls.addEventListener("start", () => (this.framed = true));
    this.counts = { voxels: 0, pathPoints: 0, trajectories: 0 };

    this.scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(-10, -20, 30);
    this.scene.add(sun);
    const grid = new THREE.GridHelper(60, 60, 0xb0b8c0, 0xdde2e6);
    grid.rotation.x = Math.PI / 2;
    this.scene.add(grid);
    this.scene.add(new THREE.AxesHelper(1.5));

    this.voxels = new VoxelLayer(this.scene);
    this.vehicle = makeVehicle();
    this.vehicle.visible = false;
    this.scene.add(this.vehicle);
    this.path = makePathLine();
    this.scene.add(this.path.line);
    this.trajectories = [];
    this.target = marker(0.18, "#d946ef");
    this.goal = marker(0.35, "#d4a017");
    this.scene.add(this.target, this.goal);
    this.ray = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ linewidth: 2 }));
    this.ray.visible = false;
    this.blocked = marker(0.12, AWARENESS_COLORS.blocked);
    this.scene.add(this.ray, this.blocked);
    this.debug = new DebugLayer(this.scene);

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    const loop = () => {
      this.render();
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  render() {
    if (this.follow && this.vehicle.visible) {
      const offset = this.camera.position.clone().sub(this.controls.target);
      this.controls.target.lerp(this.vehicle.position, 0.2);
      this.camera.position.copy(this.controls.target).add(offset);
    }
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  onVoxels(message) {
    this.voxels.apply(message);
    this.counts.voxels = this.voxels.count;
  }

  onOdometry(odometry) {
    const [w, x, y, z] = odometry.orientation;
    this.vehicle.position.set(...odometry.position);
    this.vehicle.quaternion.set(x, y, z, w);
    this.vehicle.visible = true;
  }

  onFlownPath(message) {
    const p = this.path;
    if (message.snapshot) p.count = 0;
    const color = new THREE.Color();
    for (let i = 0; i < message.speed.length && p.count < MAX_PATH_POINTS; i += 1) {
      p.positions.set(message.points.slice(3 * i, 3 * i + 3), 3 * p.count);
      speedColor(message.speed[i], MAX_SPEED_MPS, color).toArray(p.colors, 3 * p.count);
      p.count += 1;
    }
    p.line.geometry.setDrawRange(0, p.count);
    p.line.geometry.attributes.position.needsUpdate = true;
    p.line.geometry.attributes.color.needsUpdate = true;
    this.counts.pathPoints = p.count;
  }

  onTrajectory(trajectory) {
    for (const old of this.trajectories) {
      old.material.opacity = 0.25;
      old.material.transparent = true;
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(trajectory.points, 3));
    const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: modeColor(trajectory.mode_name) }));
    line.userData = trajectory;
    line.visible = !this.hidden?.has("trajectories");
    this.scene.add(line);
    this.trajectories.push(line);
    while (this.trajectories.length > KEPT_TRAJECTORIES) {
      const gone = this.trajectories.shift();
      this.scene.remove(gone);
      gone.geometry.dispose();
    }
    this.counts.trajectories += 1;
  }

  onAwareness(awareness) {
    this.ray.geometry.setFromPoints([new THREE.Vector3(...awareness.position), new THREE.Vector3(...awareness.ray_end)]);
    this.ray.material.color.set(AWARENESS_COLORS[awareness.reason_name] ?? "#000000");
    const shown = !this.hidden?.has("ray");
    this.ray.visible = shown;
    this.blocked.visible = shown && awareness.first_blocked !== null;
    if (awareness.first_blocked) this.blocked.position.set(...awareness.first_blocked);
    this.goal.position.set(...awareness.goal);
    this.goal.visible = true;
  }

  // Looks at the whole mission: start and goal in view, from the side and above.
  frame(from, to) {
    if (this.framed) return;
    this.framed = true;
    const a = new THREE.Vector3(...from);
    const b = new THREE.Vector3(...to);
    const middle = a.clone().add(b).multiplyScalar(0.5);
    const d = Math.max(8, a.distanceTo(b));
    this.controls.target.copy(middle);
    this.camera.position.copy(middle).add(new THREE.Vector3(-0.15 * d, -0.8 * d, 0.55 * d));
  }

  onPlanRequest(request) {
    this.frame(this.path.count > 0 ? Array.from(this.path.positions.slice(0, 3)) : request.start, request.goal);
    this.target.position.set(...request.target);
    this.target.visible = true;
    this.goal.position.set(...request.goal);
    this.goal.visible = true;
  }

  onDecision(decision) {
    if (decision.outcome !== "committed") return;
    this.target.position.set(...decision.local_target);
    this.target.visible = true;
  }

  onPlanDebug(debug) {
    this.debug.onPlanDebug(debug);
  }

  // Back to an empty scene (the camera stays where it is).
  reset() {
    this.voxels.apply({ snapshot: true, resolution: this.voxels.resolution, added: [], removed: [] });
    this.path.count = 0;
    this.path.line.geometry.setDrawRange(0, 0);
    for (const old of this.trajectories) {
      this.scene.remove(old);
      old.geometry.dispose();
    }
    this.trajectories = [];
    for (const o of [this.vehicle, this.target, this.goal, this.ray, this.blocked]) o.visible = false;
    this.debug.reset();
    this.counts = { voxels: 0, pathPoints: 0, trajectories: 0 };
  }

  setLayerVisible(layer, visible) {
    this.hidden = this.hidden ?? new Set();
    if (visible) this.hidden.delete(layer);
    else this.hidden.add(layer);
    const objects = {
      voxels: [this.voxels.mesh],
      path: [this.path.line],
      trajectories: this.trajectories,
      ray: [this.ray, this.blocked],
      debug: [this.debug.group],
    }[layer];
    for (const o of objects ?? []) o.visible = visible;
  }
}

function marker(radius, color) {
  const m = new THREE.Mesh(new THREE.SphereGeometry(radius, 20, 12), new THREE.MeshLambertMaterial({ color }));
  m.visible = false;
  return m;
}

function makePathLine() {
  const positions = new Float32Array(3 * MAX_PATH_POINTS);
  const colors = new Float32Array(3 * MAX_PATH_POINTS);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3).setUsage(THREE.DynamicDrawUsage));
  geometry.setAttribute("color", new THREE.BufferAttribute(colors, 3).setUsage(THREE.DynamicDrawUsage));
  geometry.setDrawRange(0, 0);
  const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ vertexColors: true }));
  line.frustumCulled = false;
  return { line, positions, colors, count: 0 };
}

// A quadrotor (body x forward) with the depth camera's frustum (80 x 60 degrees, drawn 2 m deep).
function makeVehicle() {
  const group = new THREE.Group();
  const body = new THREE.Mesh(new THREE.BoxGeometry(0.3, 0.18, 0.08), new THREE.MeshLambertMaterial({ color: "#1e293b" }));
  group.add(body);
  const nose = new THREE.Mesh(new THREE.ConeGeometry(0.06, 0.2, 12), new THREE.MeshLambertMaterial({ color: "#ef4444" }));
  nose.rotation.z = -Math.PI / 2;
  nose.position.x = 0.25;
  group.add(nose);
  for (const [x, y] of [[0.2, 0.2], [0.2, -0.2], [-0.2, 0.2], [-0.2, -0.2]]) {
    const rotor = new THREE.Mesh(new THREE.CylinderGeometry(0.11, 0.11, 0.02, 20), new THREE.MeshLambertMaterial({ color: "#64748b" }));
    rotor.rotation.x = Math.PI / 2;
    rotor.position.set(x, y, 0.04);
    group.add(rotor);
  }
  const depth = 2.0;
  const hx = depth * Math.tan((40 * Math.PI) / 180);
  const hz = depth * Math.tan((30 * Math.PI) / 180);
  const corners = [[depth, hx, hz], [depth, -hx, hz], [depth, -hx, -hz], [depth, hx, -hz]].map((c) => new THREE.Vector3(...c));
  const points = [];
  for (let i = 0; i < 4; i += 1) points.push(new THREE.Vector3(), corners[i], corners[i], corners[(i + 1) % 4]);
  const frustum = new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(points), new THREE.LineBasicMaterial({ color: "#0ea5e9" }));
  group.add(frustum);
  return group;
}
