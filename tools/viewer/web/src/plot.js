// A small time plot on a canvas: series of (t, value) points, drawn as lines or dots, with the
// axis range and the latest value written in the corner.
export class TimePlot {
  constructor(canvas, { title, unit, dots = false }) {
    this.canvas = canvas;
    this.title = title;
    this.unit = unit;
    this.dots = dots;
    this.series = new Map(); // name -> { color, t: [], v: [] }
    this.dirty = true;
    const loop = () => {
      if (this.dirty) this.draw();
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  add(name, color, t, v) {
    let s = this.series.get(name);
    if (!s) {
      s = { color, t: [], v: [] };
      this.series.set(name, s);
    }
    s.t.push(t);
    s.v.push(v);
    this.dirty = true;
  }

  clear() {
    this.series.clear();
    this.dirty = true;
  }

  draw() {
    this.dirty = false;
    const c = this.canvas;
    const w = (c.width = c.clientWidth * devicePixelRatio);
    const h = (c.height = c.clientHeight * devicePixelRatio);
    const g = c.getContext("2d");
    g.clearRect(0, 0, w, h);
    let t0 = Infinity, t1 = -Infinity, vmax = 0, last = null;
    for (const s of this.series.values()) {
      for (let i = 0; i < s.t.length; i += 1) {
        t0 = Math.min(t0, s.t[i]);
        t1 = Math.max(t1, s.t[i]);
        vmax = Math.max(vmax, s.v[i]);
      }
      if (s.v.length) last = s.v[s.v.length - 1];
    }
    g.fillStyle = "#334155";
    g.font = `${11 * devicePixelRatio}px sans-serif`;
    g.fillText(`${this.title}${last !== null ? `: ${last.toFixed(2)} ${this.unit}` : ""}`, 4, 12 * devicePixelRatio);
    if (!Number.isFinite(t0)) return;
    vmax = vmax > 0 ? vmax * 1.1 : 1;
    const span = Math.max(1e-3, t1 - t0);
    const pad = 16 * devicePixelRatio;
    const x = (t) => ((t - t0) / span) * (w - 8) + 4;
    const y = (v) => h - 4 - (v / vmax) * (h - pad - 4);
    g.fillText(`${vmax.toFixed(1)} ${this.unit}, ${span.toFixed(0)} s`, w - 90 * devicePixelRatio, 12 * devicePixelRatio);
    for (const s of this.series.values()) {
      g.strokeStyle = g.fillStyle = s.color;
      g.lineWidth = devicePixelRatio;
      if (this.dots) {
        for (let i = 0; i < s.t.length; i += 1) g.fillRect(x(s.t[i]) - 2, y(s.v[i]) - 2, 4, 4);
        continue;
      }
      g.beginPath();
      for (let i = 0; i < s.t.length; i += 1) (i ? g.lineTo : g.moveTo).call(g, x(s.t[i]), y(s.v[i]));
      g.stroke();
    }
  }
}
