// The health panel: one row per service process from HEARTBEAT. A process is alive while its
// heartbeats keep coming (within 3 s of this page's clock), silent after. For a recorded flight
// (useMessageClock) the clock is the time shown: alive if a heartbeat came in the 3 s before it.
const SILENT_AFTER_MS = 3000;

export class HealthPanel {
  constructor(tbody) {
    this.tbody = tbody;
    this.rows = new Map();
    this.messageClock = null; // () => seconds of the message clock, or null: this page's clock
    setInterval(() => this.refreshAges(), 500);
  }

  useMessageClock(now) {
    this.messageClock = now;
  }

  reset() {
    this.rows.clear();
    this.tbody.innerHTML = "";
  }

  onHeartbeat(hb) {
    const key = `${hb.service}@${hb.host}:${hb.pid}`;
    let row = this.rows.get(key);
    if (!row) {
      row = { tr: document.createElement("tr") };
      row.tr.className = "health-row";
      this.rows.set(key, row);
      const ordered = [...this.rows.entries()].sort(([a], [b]) => a.localeCompare(b));
      for (const [, r] of ordered) this.tbody.appendChild(r.tr);
    }
    row.heartbeat = hb;
    row.receivedMs = performance.now();
    const rejected = Object.entries(hb.counters)
      .filter(([name, value]) => name.startsWith("rejected_") && value > 0)
      .map(([name, value]) => `${name.slice(9)} ${value}`)
      .join(", ");
    row.tr.dataset.service = hb.service;
    row.tr.dataset.state = hb.state;
    row.tr.title = `${hb.host} pid ${hb.pid}, up ${hb.uptime_s} s${hb.detail ? ": " + hb.detail : ""}`;
    row.tr.innerHTML = "";
    for (const text of [hb.service, hb.state, hb.msgs_in, hb.msgs_out, hb.msgs_rejected, rejected || "-"]) {
      const td = document.createElement("td");
      td.textContent = String(text);
      row.tr.appendChild(td);
    }
    this.refreshAges();
  }

  refreshAges() {
    const now = performance.now();
    for (const row of this.rows.values()) {
      const alive = this.messageClock
        ? this.messageClock() - row.heartbeat.t < SILENT_AFTER_MS / 1000
        : now - row.receivedMs < SILENT_AFTER_MS;
      row.tr.dataset.alive = alive ? "true" : "false";
      row.tr.classList.toggle("silent", !alive);
      row.tr.classList.toggle("degraded", alive && row.heartbeat.state !== "OK");
    }
  }

  aliveCount() {
    return [...this.rows.values()].filter((r) => r.tr.dataset.alive === "true").length;
  }
}
