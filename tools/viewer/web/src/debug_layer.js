// The debug layer (PLAN_DEBUG, when the planners publish it): for the latest plan of each mode,
// SOM's A* path and corridor polytopes (translucent green hulls with their edges), EAM's A*
// guides, B-spline control points and {p, v} anchor pairs (an arrow along v at p, and a thin
// line from the control point it pushes).
import * as THREE from "three";
import { ConvexGeometry } from "three/addons/geometries/ConvexGeometry.js";

const SOM_PATH = "#166534";
const CORRIDOR = "#22c55e";
const EAM_GUIDE = "#9a3412";
const CONTROL_POINT = "#c2410c";
const PAIR = "#7c3aed";
const ARROW_M = 0.3;

export class DebugLayer {
  constructor(parent) {
    this.group = new THREE.Group();
    parent.add(this.group);
    this.byMode = new Map(); // mode name -> THREE.Group of its latest plan
    this.counts = { polytopes: 0, paths: 0, pairs: 0, controlPoints: 0 };
  }

  onPlanDebug(debug) {
    this.remove(debug.mode_name);
    const g = new THREE.Group();
    g.userData = { request_id: debug.request_id, ok: debug.ok };
    const pathColor = debug.mode_name === "SOM" ? SOM_PATH : EAM_GUIDE;
    for (const path of debug.paths) {
      if (path.length >= 6) g.add(line(path, pathColor, { dashed: debug.mode_name === "EAM" }));
    }
    for (const vertices of debug.polytopes) {
      const points = [];
      for (let i = 0; i + 2 < vertices.length; i += 3) points.push(new THREE.Vector3(vertices[i], vertices[i + 1], vertices[i + 2]));
      if (points.length < 4) continue;
      let hull;
      try {
        hull = new ConvexGeometry(points);
      } catch {
        continue; // a flat set of points has no hull
      }
      const mesh = new THREE.Mesh(hull, new THREE.MeshBasicMaterial({ color: CORRIDOR, transparent: true, opacity: 0.08, depthWrite: false, side: THREE.DoubleSide }));
      mesh.userData.kind = "polytope";
      g.add(mesh);
      g.add(new THREE.LineSegments(new THREE.EdgesGeometry(hull), new THREE.LineBasicMaterial({ color: CORRIDOR, transparent: true, opacity: 0.5 })));
    }
    const q = debug.control_points;
    if (q.length >= 3) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.Float32BufferAttribute(q, 3));
      g.add(new THREE.Points(geometry, new THREE.PointsMaterial({ color: CONTROL_POINT, size: 0.08 })));
    }
    const pairLines = [];
    for (let i = 0; i < debug.pair_control_point.length; i += 1) {
      const p = new THREE.Vector3(...debug.pair_p.slice(3 * i, 3 * i + 3));
      const v = new THREE.Vector3(...debug.pair_v.slice(3 * i, 3 * i + 3)).normalize();
      g.add(new THREE.ArrowHelper(v, p, ARROW_M, PAIR, 0.08, 0.05));
      const k = debug.pair_control_point[i];
      pairLines.push(q[3 * k], q[3 * k + 1], q[3 * k + 2], p.x, p.y, p.z);
    }
    if (pairLines.length) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.Float32BufferAttribute(pairLines, 3));
      g.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: PAIR, transparent: true, opacity: 0.4 })));
    }
    g.userData.counts = {
      polytopes: g.children.filter((o) => o.userData.kind === "polytope").length,
      paths: debug.paths.length,
      pairs: debug.pair_control_point.length,
      controlPoints: q.length / 3,
    };
    this.byMode.set(debug.mode_name, g);
    this.group.add(g);
    this.recount();
  }

  remove(mode) {
    const old = this.byMode.get(mode);
    if (!old) return;
    this.group.remove(old);
    old.traverse((o) => {
      o.geometry?.dispose();
      o.material?.dispose();
    });
    this.byMode.delete(mode);
  }

  reset() {
    for (const mode of [...this.byMode.keys()]) this.remove(mode);
    this.recount();
  }

  recount() {
    const c = { polytopes: 0, paths: 0, pairs: 0, controlPoints: 0 };
    for (const g of this.byMode.values()) for (const k of Object.keys(c)) c[k] += g.userData.counts[k];
    this.counts = c;
  }
}

function line(flat, color, { dashed = false } = {}) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(flat, 3));
  const material = dashed
    ? new THREE.LineDashedMaterial({ color, dashSize: 0.15, gapSize: 0.08 })
    : new THREE.LineBasicMaterial({ color });
  const l = new THREE.Line(geometry, material);
  if (dashed) l.computeLineDistances();
  return l;
}
