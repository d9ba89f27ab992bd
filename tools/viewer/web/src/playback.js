// The time slider of a recorded flight (mmh-viewer --log): play/pause, the time shown and the
// speed. Moving the slider asks the server to jump there (playback.time); the server answers
// with /mmh/playback, whose generation changes on every jump (main.js then rebuilds the scene
// from the snapshots that follow, until the same generation comes again with ready).
export class PlaybackBar {
  constructor(root, setParameters) {
    this.root = root;
    this.setParameters = setParameters;
    this.slider = root.querySelector("#playback-slider");
    this.button = root.querySelector("#playback-play");
    this.label = root.querySelector("#playback-time");
    this.speed = root.querySelector("#playback-speed");
    this.state = null;
    this.dragging = false;
    this.slider.addEventListener("input", () => {
      this.dragging = true;
      this.label.textContent = this.format(Number(this.slider.value));
      this.setParameters([{ name: "playback.time", value: Number(this.slider.value) }]);
    });
    this.slider.addEventListener("change", () => (this.dragging = false));
    this.button.addEventListener("click", () =>
      this.setParameters([{ name: "playback.playing", value: !(this.state?.playing ?? false) }]));
    this.speed.addEventListener("change", () =>
      this.setParameters([{ name: "playback.speed", value: Number(this.speed.value) }]));
  }

  show() {
    this.root.hidden = false;
    document.body.dataset.playback = "log";
  }

  onPlayback(state) {
    this.state = state;
    this.slider.min = state.start_t;
    this.slider.max = state.end_t;
    this.slider.step = "any";
    if (!this.dragging) this.slider.value = state.t;
    this.button.textContent = state.playing ? "pause" : "play";
    this.label.textContent = this.format(state.t);
    const d = document.body.dataset;
    d.playbackTime = state.t.toFixed(3);
    d.playing = state.playing;
    d.generation = state.generation;
    if (state.ready) d.readyGeneration = state.generation;
  }

  format(t) {
    const s = this.state;
    return s ? `${(t - s.start_t).toFixed(1)} / ${(s.end_t - s.start_t).toFixed(1)} s` : "";
  }
}
