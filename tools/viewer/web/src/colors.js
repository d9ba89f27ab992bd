// Colours shared by the 3D scene, the timeline and the plots.
import * as THREE from "three";

// Committed trajectories and decisions, by the mode that made them.
export const MODE_COLORS = { FPM: "#1f77b4", SOM: "#2ca02c", EAM: "#ff7f0e", STOP: "#7f7f7f", "-": "#bbbbbb" };
// The sensing ray as in the paper's Fig. 2.
export const AWARENESS_COLORS = { clear: "#22c55e", narrow: "#eab308", blocked: "#ef4444" };
export const OUTCOME_COLORS = { failed: "#dc2626", stopping: "#7f7f7f", reached: "#d4a017", rejected: "#9333ea" };

export function modeColor(name) {
  return MODE_COLORS[name] ?? MODE_COLORS["-"];
}

export function decisionColor(decision) {
  if (decision.outcome === "committed") return modeColor(decision.committed_mode);
  return OUTCOME_COLORS[decision.outcome] ?? "#444444";
}

// Blue (slow) to red (fast), as the flown path in the paper's Fig. 8.
export function speedColor(speed, maxSpeed, target = new THREE.Color()) {
  const f = Math.min(1, Math.max(0, speed / maxSpeed));
  return target.setHSL((1 - f) * 0.66, 0.9, 0.5);
}

// Occupied voxels by height over the map's usual 0-4 m.
export function heightColor(z, target = new THREE.Color()) {
  const f = Math.min(1, Math.max(0, z / 4));
  return target.setHSL(0.75 - 0.75 * f, 0.65, 0.45 + 0.1 * f);
}
