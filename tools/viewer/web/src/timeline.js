// The decision timeline: one mark per ARBITER_STATUS along the flight's time, coloured by outcome
// and committed mode; clicking a mark shows the decision and the answers of the modes asked.
import { decisionColor } from "./colors.js";

export class Timeline {
  constructor(strip, details) {
    this.strip = strip;
    this.details = details;
    this.decisions = [];
    this.results = new Map(); // request id -> answers of the modes
    this.selected = null;
    this.span = null; // [t0, t1] of a recorded flight; null: the decisions' own span
  }

  // A recorded flight: marks along its whole time, as the slider above.
  setSpan(t0, t1) {
    this.span = [t0, t1];
    this.layout();
  }

  reset() {
    for (const d of this.decisions) d.mark.remove();
    this.decisions = [];
    this.results.clear();
    this.selected = null;
    this.details.innerHTML = '<p class="hint">Click a mark on the timeline for the decision.</p>';
  }

  onPlanResult(result) {
    const list = this.results.get(result.request_id) ?? [];
    list.push(result);
    this.results.set(result.request_id, list);
    if (this.selected && this.selected.request_id === result.request_id) this.show(this.selected);
  }

  onDecision(decision) {
    this.decisions.push(decision);
    const mark = document.createElement("div");
    mark.className = "mark";
    mark.dataset.outcome = decision.outcome;
    mark.style.background = decisionColor(decision);
    mark.title = `#${decision.seq} ${decision.trigger} → ${decision.outcome} ${decision.committed_mode}`;
    mark.addEventListener("click", () => this.show(decision, mark));
    decision.mark = mark;
    this.strip.appendChild(mark);
    this.layout();
  }

  layout() {
    if (this.decisions.length === 0) return;
    const [t0, t1] = this.span ?? [this.decisions[0].t, this.decisions[this.decisions.length - 1].t];
    const span = Math.max(1, t1 - t0);
    for (const d of this.decisions) d.mark.style.left = `calc(${(100 * (d.t - t0)) / span}% - 4px)`;
  }

  show(decision, mark = decision.mark) {
    this.selected = decision;
    for (const m of this.strip.querySelectorAll(".mark.selected")) m.classList.remove("selected");
    mark.classList.add("selected");
    const ms = decision.compute_ms;
    const answers = (this.results.get(decision.request_id) ?? [])
      .map((r) => `<li>${r.mode_name}: ${r.ok ? "ok" : "failed"} in ${r.compute_ms.toFixed(2)} ms${r.narrow ? " (narrow)" : ""}${r.detail ? " — " + escapeHtml(r.detail) : ""}</li>`)
      .join("");
    this.details.innerHTML = `
      <h3>Decision #${decision.seq} at ${decision.t.toFixed(2)} s</h3>
      <table>
        <tr><th>trigger</th><td>${decision.trigger}</td></tr>
        <tr><th>outcome</th><td>${decision.outcome} ${decision.committed_mode}</td></tr>
        <tr><th>awareness</th><td>${decision.awareness_safe ? "safe" : "unsafe"} (${decision.awareness_reason})</td></tr>
        <tr><th>modes asked</th><td>${decision.modes_asked}</td></tr>
        <tr><th>answered ok</th><td>${decision.modes_answered_ok}</td></tr>
        <tr><th>compute</th><td>FPM ${ms.FPM} ms, SOM ${ms.SOM} ms, EAM ${ms.EAM} ms</td></tr>
        <tr><th>request</th><td>${decision.request_id} → trajectory ${decision.trajectory_id}</td></tr>
        ${decision.reaction_ms >= 0 ? `<tr><th>reaction</th><td>${decision.reaction_ms.toFixed(1)} ms after the scan that showed the danger</td></tr>` : ""}
        <tr><th>reason</th><td>${escapeHtml(decision.detail || "-")}</td></tr>
      </table>
      <ul class="answers">${answers}</ul>`;
  }
}

function escapeHtml(text) {
  return text.replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
}
