// mmh-viewer's page: connects to the server it was loaded from and routes each channel's
// messages to the 3D scene, the health panel, the timeline and the plots; for a recorded flight
// (mmh-viewer --log) also to the time slider, and a jump of the slider rebuilds the page from the
// snapshots that follow. The page's state is also in the DOM (data-* attributes of <body>) for
// tests and scripts.
import { connect } from "./connection.js";
import { AWARENESS_COLORS, modeColor } from "./colors.js";
import { HealthPanel } from "./health.js";
import { PlaybackBar } from "./playback.js";
import { TimePlot } from "./plot.js";
import { Scene3D } from "./scene3d.js";
import { Timeline } from "./timeline.js";

const $ = (id) => document.getElementById(id);
const scene = new Scene3D($("scene"));
const health = new HealthPanel($("health-rows"));
const timeline = new Timeline($("timeline"), $("decision"));
const speedPlot = new TimePlot($("plot-speed"), { title: "speed", unit: "m/s" });
const accelerationPlot = new TimePlot($("plot-acceleration"), { title: "acceleration", unit: "m/s²" });
const planningPlot = new TimePlot($("plot-planning"), { title: "planning time", unit: "ms", dots: true });
const newCounts = () => ({ messages: 0, decisions: 0, heartbeats: 0, odometry: 0 });
let counts = newCounts();
let generation = null; // of /mmh/playback: a new one means the scene jumped

// Empties everything the messages built (the snapshots of the new time follow).
function reset() {
  scene.reset();
  health.reset();
  timeline.reset();
  for (const plot of [speedPlot, accelerationPlot, planningPlot]) plot.clear();
  counts = newCounts();
  for (const id of ["vehicle", "mission", "trajectory", "awareness"]) $(id).textContent = "-";
  delete document.body.dataset.mission;
}

const handlers = {
  "/mmh/map_voxels": (m) => scene.onVoxels(m),
  "/mmh/odometry": (m) => {
    counts.odometry += 1;
    scene.onOdometry(m);
    $("vehicle").textContent = `t ${m.t.toFixed(1)} s   ${m.position.map((v) => v.toFixed(1)).join(", ")} m   ${m.speed.toFixed(2)} m/s`;
  },
  "/mmh/flown_path": (m) => {
    if (m.snapshot) {
      speedPlot.clear();
      accelerationPlot.clear();
    }
    scene.onFlownPath(m);
    for (let i = 0; i < m.t.length; i += 1) {
      speedPlot.add("speed", "#2563eb", m.t[i], m.speed[i]);
      accelerationPlot.add("acceleration", "#9333ea", m.t[i], m.acceleration[i]);
    }
  },
  "/mmh/trajectory": (m) => {
    scene.onTrajectory(m);
    $("trajectory").innerHTML = `<span class="swatch" style="background:${modeColor(m.mode_name)}"></span>${m.mode_name} #${m.id}, ${m.duration_s.toFixed(1)} s, max ${m.max_speed.toFixed(2)} m/s`;
  },
  "/mmh/awareness": (m) => {
    scene.onAwareness(m);
    $("awareness").innerHTML = `<span class="swatch" style="background:${AWARENESS_COLORS[m.reason_name]}"></span>${m.reason_name}`;
  },
  "/mmh/plan_request": (m) => scene.onPlanRequest(m),
  "/mmh/plan_result": (m) => {
    timeline.onPlanResult(m);
    planningPlot.add(m.mode_name, modeColor(m.mode_name), m.t, m.compute_ms);
  },
  "/mmh/plan_debug": (m) => scene.onPlanDebug(m),
  "/mmh/decision": (m) => {
    counts.decisions += 1;
    scene.onDecision(m);
    timeline.onDecision(m);
  },
  "/mmh/heartbeat": (m) => {
    counts.heartbeats += 1;
    health.onHeartbeat(m);
  },
  "/mmh/mission": (m) => {
    const state = m.collided ? "collided" : m.reached ? "goal reached" : m.active ? "flying" : "idle";
    document.body.dataset.mission = state;
    $("mission").textContent = `${state}, ${m.flight_time_s.toFixed(1)} s, ${m.distance_m.toFixed(1)} m, clearance ${m.min_clearance_m.toFixed(2)} m`;
  },
  "/mmh/playback": (m) => {
    if (generation !== null && m.generation !== generation) reset();
    generation = m.generation;
    timeline.setSpan(m.start_t, m.end_t);
    if (m.ready) showCounts(); // the scene of this time is complete: the DOM says so at once
    playback.onPlayback(m);
  },
};

const url = `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/`;
const link = connect(url, {
  onStatus: (status) => {
    $("connection").textContent = status;
    document.body.dataset.connection = status;
  },
  onChannels: (topics) => {
    if (!topics.includes("/mmh/playback")) return;
    playback.show();
    health.useMessageClock(() => playback.state?.t ?? 0);
  },
  onMessage: (topic, payload) => {
    counts.messages += 1;
    handlers[topic]?.(payload);
  },
});
const playback = new PlaybackBar($("playback"), (parameters) => link.setParameters(parameters));

$("follow").addEventListener("change", (e) => (scene.follow = e.target.checked));
for (const box of document.querySelectorAll("input[data-layer]"))
  box.addEventListener("change", (e) => scene.setLayerVisible(e.target.dataset.layer, e.target.checked));

function showCounts() {
  const d = document.body.dataset;
  d.messages = counts.messages;
  d.voxels = scene.counts.voxels;
  d.pathPoints = scene.counts.pathPoints;
  d.trajectories = scene.counts.trajectories;
  d.decisions = counts.decisions;
  d.servicesAlive = health.aliveCount();
  d.odometry = counts.odometry;
  d.debugPolytopes = scene.debug.counts.polytopes;
  d.debugPaths = scene.debug.counts.paths;
  d.debugPairs = scene.debug.counts.pairs;
}
setInterval(showCounts, 250);
