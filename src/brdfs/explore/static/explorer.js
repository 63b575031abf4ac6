// brdfs explorer: the page. Plain JavaScript, canvas drawing, no library; every number comes from the
// server (brdfs.explore.server), which computes it with the package.
"use strict";

const SIDES = ["left", "right"];
const SLIDER_STEPS = 1000;
const state = { catalogue: null, byName: {}, theta: 30, lobeMode: "fcos", yaw: -35, pitch: 25, panels: {} };
// what the browser tests read: the last answer of every view, and whether anything is in flight
window.explorer = { ready: false, last: { left: {}, right: {} }, busy: () => Object.values(state.panels).some((p) => p.busy()) };

// --- messages: one line in the page, from whichever view failed last ---------------------------------
const problems = new Map();   // source -> {text, kind}
function setProblem(source, text, kind = "error") {
  if (text) problems.set(source, { text, kind }); else problems.delete(source);
  const box = document.getElementById("message");
  const shown = [...problems.values()].find((p) => p.kind === "error") || [...problems.values()][0];
  box.hidden = !shown;
  box.textContent = shown ? shown.text : "";
  box.className = shown ? shown.kind : "";
}

// --- a channel per view and side: the newest request wins, one in flight at a time ---------------------
class Channel {
  constructor(name, figure, draw) { Object.assign(this, { name, figure, draw, want: null, inFlight: false, started: 0 }); }
  request(url) { this.want = url; if (!this.inFlight) this.pump(); }
  async pump() {
    while (this.want) {
      const url = this.want;
      this.want = null;
      this.inFlight = true;
      this.started = performance.now();
      this.figure.classList.add("computing");
      updateStatus();
      let data, error;
      try {
        const response = await fetch(url);
        data = await response.json();
        if (!response.ok) error = data.error || `${response.status} ${response.statusText}`;
      } catch (err) {
        error = `the server did not answer (${err.message}): is brdfs explore still running?`;
      }
      this.inFlight = false;
      this.figure.classList.remove("computing");
      if (error) { setProblem(this.name, error); } else { setProblem(this.name, null); this.draw(data, url); }
      updateStatus();
    }
  }
}

function updateStatus() {
  for (const panel of Object.values(state.panels)) panel.showStatus();
}
setInterval(updateStatus, 250);

// --- number formatting and slider scales ------------------------------------------------------------
const fmt = (x, digits = 4) => (x === null || x === undefined ? "—" : Number(x).toPrecision(digits).replace(/\.?0+(e|$)/, "$1"));
function toSlider(p, value) {
  const [lo, hi] = p.slider;
  const t = p.log ? Math.log(value / lo) / Math.log(hi / lo) : (value - lo) / (hi - lo);
  return Math.round(Math.min(1, Math.max(0, t)) * SLIDER_STEPS);
}
function fromSlider(p, position) {
  const [lo, hi] = p.slider;
  const t = position / SLIDER_STEPS;
  return Number((p.log ? lo * Math.pow(hi / lo, t) : lo + t * (hi - lo)).toPrecision(4));
}

// --- a panel: one model's controls and views --------------------------------------------------------
class Panel {
  constructor(side) {
    this.side = side;
    this.values = {};       // parameter -> text sent to the server (absent: the model's default)
    this.root = document.createElement("section");
    this.root.className = "panel";
    this.root.id = `panel-${side}`;
    this.root.innerHTML = `
      <h2><span class="name"></span> <span class="doc"></span></h2>
      <div class="controls"></div>
      <div class="status"></div>
      <div class="views">
        <figure class="lobe"><canvas width="380" height="250"></canvas><figcaption>Lobe in the plane of incidence</figcaption></figure>
        <figure class="albedo"><canvas width="380" height="250"></canvas><figcaption class="albedo-caption">Albedo a(θ<sub>L</sub>)</figcaption></figure>
        <figure class="sphere"><img class="sphere" alt="lit sphere"><figcaption>Lit sphere: light at θ<sub>L</sub> from the view, plus sky</figcaption></figure>
        <figure class="slice"><div class="slice-box"><span class="axis-y">θ<sub>d</sub> 0° → 90°</span><img class="slice" alt="image slice"></div>
          <figcaption class="slice-caption">f over θ<sub>h</sub> 0° → 90° (x), θ<sub>d</sub> (y), φ<sub>d</sub> = 90°, log scale</figcaption></figure>
      </div>`;
    const fig = (cls) => this.root.querySelector(`figure.${cls}`);
    this.channels = {
      albedo: new Channel(`${side}:albedo`, fig("albedo"), (d) => { this.albedo = d; this.drawAlbedo(); this.reportAlbedo(); }),
      lobe: new Channel(`${side}:lobe`, fig("lobe"), (d) => { this.lobe = d; this.drawLobe(); }),
      sphere: new Channel(`${side}:sphere`, fig("sphere"), (d) => { this.root.querySelector("img.sphere").src = "data:image/png;base64," + d.png; }),
      slice: new Channel(`${side}:slice`, fig("slice"), (d) => this.drawSlice(d)),
    };
    const lobeCanvas = this.root.querySelector("figure.lobe canvas");
    let drag = null;
    lobeCanvas.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; lobeCanvas.setPointerCapture(e.pointerId); });
    lobeCanvas.addEventListener("pointerup", () => { drag = null; });
    lobeCanvas.addEventListener("pointermove", (e) => {
      if (!drag || state.lobeMode !== "3d") return;
      state.yaw += e.clientX - drag[0];
      state.pitch = Math.max(-10, Math.min(89, state.pitch + (e.clientY - drag[1])));
      drag = [e.clientX, e.clientY];
      for (const panel of Object.values(state.panels)) panel.drawLobe();
    });
    for (const [view, channel] of Object.entries(this.channels)) {
      const draw = channel.draw;
      channel.draw = (d, url) => { window.explorer.last[side][view] = { data: d, url }; draw(d); };
    }
  }

  requestLobe() {
    const view = state.lobeMode === "3d" ? "lobe3d" : "lobe";
    this.channels.lobe.request(`/api/${view}?${this.query({ theta: state.theta })}`);
  }

  busy() { return Object.values(this.channels).some((c) => c.inFlight || c.want); }

  setModel(name, values = {}) {
    this.model = state.byName[name];
    this.values = {};
    for (const [k, v] of Object.entries(values)) this.values[k] = v;
    this.albedo = this.lobe = null;
    this.root.querySelector(".name").textContent = name;
    this.root.querySelector(".doc").textContent = this.model.doc || "";
    this.buildControls();
    this.refresh(true);
  }

  buildControls() {
    const box = this.root.querySelector(".controls");
    box.innerHTML = "";
    for (const p of this.model.params) {
      const label = el("label", { textContent: p.name, title: `declared range ${interval(p)}` });
      const slider = el("input", { type: "range", min: 0, max: SLIDER_STEPS, step: 1, name: p.name });
      const number = el("input", { type: "number", step: "any", name: p.name });
      const auto = el("label", { className: "scale" });
      const start = this.values[p.name] !== undefined ? Number(this.values[p.name]) : p.default;
      let autoBox = null;
      if (p.default === null) {   // the model computes it unless given (e.g. a normalisation C)
        autoBox = el("input", { type: "checkbox", checked: this.values[p.name] === undefined });
        auto.append(autoBox, " auto");
        autoBox.addEventListener("change", () => {
          if (autoBox.checked) delete this.values[p.name];
          else this.values[p.name] = number.value = fromSlider(p, Number(slider.value));
          showAuto();
          this.changed();
        });
      } else {
        auto.textContent = p.log ? "log" : "";
      }
      const shown = start === null || start === undefined ? fromSlider(p, SLIDER_STEPS / 2) : start;
      number.value = shown;
      slider.value = toSlider(p, shown);
      const showAuto = () => {     // "auto": the number box empty, the model's own value in force
        slider.disabled = number.disabled = Boolean(autoBox && autoBox.checked);
        if (number.disabled) { number.value = ""; number.placeholder = "auto"; }
      };
      showAuto();
      slider.addEventListener("input", () => {
        number.value = fromSlider(p, Number(slider.value));
        this.values[p.name] = number.value;
        this.changed();
      });
      number.addEventListener("change", () => {
        this.values[p.name] = number.value.trim() || "nan";
        const v = Number(number.value);
        if (Number.isFinite(v)) slider.value = toSlider(p, v);
        this.changed();
      });
      box.append(label, slider, number, auto);
    }
    for (const c of this.model.choices) {
      const select = el("select", { name: c.name });
      for (const v of c.values) select.append(el("option", { value: v, textContent: v }));
      select.value = this.values[c.name] !== undefined ? this.values[c.name] : c.default;
      select.addEventListener("change", () => { this.values[c.name] = select.value; this.changed(); });
      box.append(el("label", { textContent: c.name }), select, el("span"), el("span"));
    }
    if (!this.model.params.length && !this.model.choices.length) box.append(el("span", { textContent: "(no parameters)" }));
  }

  changed() { writeHash(); this.refresh(true); }

  query(extra = {}) {
    const q = new URLSearchParams({ model: this.model.name });
    for (const [k, v] of Object.entries(this.values)) q.set(`p.${k}`, v);
    for (const [k, v] of Object.entries(extra)) q.set(k, v);
    return q.toString();
  }

  refresh(parametersChanged) {
    const theta = state.theta;
    if (parametersChanged) {
      this.channels.albedo.request(`/api/albedo?${this.query()}`);
      if (this.model.isotropic) this.channels.slice.request(`/api/slice?${this.query({ size: 128 })}`);
      else this.drawSlice({ png: null, reason: `${this.model.name} is anisotropic: no (θ_h, θ_d) slice` });
    }
    this.requestLobe();
    this.channels.sphere.request(`/api/sphere?${this.query({ theta, size: 256 })}`);
    this.drawAlbedo();
  }

  showStatus() {
    const busy = Object.entries(this.channels).filter(([, c]) => c.inFlight);
    const box = this.root.querySelector(".status");
    if (busy.length) {
      const seconds = Math.max(...busy.map(([, c]) => performance.now() - c.started)) / 1000;
      box.innerHTML = `<span class="busy">computing ${busy.map(([v]) => v).join(", ")}… ${seconds.toFixed(1)} s</span>`;
    } else if (this.albedo) {
      box.textContent = `albedo: ${this.albedo.theta.length} angles in ${Math.round(this.albedo.ms)} ms, ` +
        Object.entries(this.albedo.counts).map(([s, n]) => `${n} ${s}`).join(", ");
    }
  }

  reportAlbedo() {
    const a = this.albedo;
    const missed = a.status.map((s, i) => [s, a.theta[i]]).filter(([s]) => s === "stalled" || s === "budget_exhausted");
    const text = missed.length
      ? `${this.model.name}: the albedo did not converge to rtol ${a.rtol.toExponential(0)} at ${missed.length} of ${a.theta.length} angles ` +
        `(${[...new Set(missed.map(([s]) => s))].join(", ")}, from ${fmt(missed[0][1], 3)}°); the band shows their honest error bounds`
      : null;
    setProblem(`${this.side}:albedo-status`, text, "warning");
  }

  // --- drawing ------------------------------------------------------------------------------------
  drawAlbedo() {
    const canvas = this.root.querySelector("figure.albedo canvas");
    const g = canvas.getContext("2d");
    const W = canvas.width, H = canvas.height, m = { l: 46, r: 10, t: 12, b: 30 };
    g.clearRect(0, 0, W, H);
    const a = this.albedo;
    if (!a) return;
    const vals = a.value.map((v, i) => (v === null ? null : [a.theta[i], v, a.error[i] || 0]));
    const upTo85 = vals.filter((p) => p && p[0] <= 85).map((p) => p[1] + p[2]);
    let ymax = niceCeil(Math.max(0.1, ...upTo85) * 1.15);
    const px = (t) => m.l + (t / 90) * (W - m.l - m.r);
    const py = (v) => H - m.b - (Math.min(v, ymax * 1.02) / ymax) * (H - m.t - m.b);
    axes(g, W, H, m, [0, 15, 30, 45, 60, 75, 90], ticks(ymax), px, py, "θ_L [deg]", "a(θ_L)");
    // the certified band: value ± error (drawn at least one pixel wide where the error is tiny)
    g.fillStyle = "rgba(30, 110, 220, 0.25)";
    g.beginPath();
    const pts = vals.filter(Boolean);
    pts.forEach(([t, v, e], i) => (i ? g.lineTo(px(t), py(v + e) - 0.5) : g.moveTo(px(t), py(v + e) - 0.5)));
    [...pts].reverse().forEach(([t, v, e]) => g.lineTo(px(t), py(Math.max(0, v - e)) + 0.5));
    g.closePath();
    g.fill();
    g.strokeStyle = "#1e6edc";
    g.lineWidth = 1.5;
    line(g, pts.map(([t, v]) => [px(t), py(v)]));
    // statuses: stalled / budget exhausted in orange, diverged as an arrow at the top
    a.status.forEach((s, i) => {
      const t = a.theta[i];
      if (s === "stalled" || s === "budget_exhausted") { g.fillStyle = "#e07000"; g.fillRect(px(t) - 2, py(a.value[i] || 0) - 2, 4, 4); }
      if (s === "diverged") {
        g.fillStyle = "#c00000";
        g.font = "12px system-ui";
        g.textAlign = "right";
        g.fillText("→ ∞ at " + fmt(t, 3) + "° (diverged)", px(t) - 4, m.t + 10);
        g.beginPath(); g.moveTo(px(t), m.t + 12); g.lineTo(px(t) - 4, m.t + 20); g.lineTo(px(t) + 4, m.t + 20); g.fill();
      }
    });
    // the current θ_L
    g.strokeStyle = "#999"; g.setLineDash([4, 3]);
    line(g, [[px(state.theta), m.t], [px(state.theta), H - m.b]]);
    g.setLineDash([]);
    const maxErr = Math.max(...a.error.filter((e) => e !== null));
    const cap = this.root.querySelector(".albedo-caption");
    cap.textContent = `Albedo a(θ_L), ${a.theta.length} angles, rtol ${a.rtol.toExponential(0)}: largest error bound ${fmt(maxErr, 2)} (band)`;
  }

  drawLobe() {
    const canvas = this.root.querySelector("figure.lobe canvas");
    const g = canvas.getContext("2d");
    const W = canvas.width, H = canvas.height, cx = W / 2, cy = H - 20, R = Math.min(W / 2 - 14, H - 34);
    g.clearRect(0, 0, W, H);
    const d = this.lobe;
    if (!d) return;
    this.root.querySelector("figure.lobe figcaption").textContent =
      d.phi_v ? "Lobe over the hemisphere (f cos θV)" : "Lobe in the plane of incidence";
    if (d.phi_v) { this.drawLobe3d(g, W, H, d); return; }
    const ys = (state.lobeMode === "f" ? d.f : d.fcos).map((v) => (v === null ? 0 : v));
    const top = Math.max(...ys) || 1;
    g.strokeStyle = "#ddd"; g.lineWidth = 1;
    for (const r of [0.25, 0.5, 0.75, 1]) { g.beginPath(); g.arc(cx, cy, R * r, Math.PI, 2 * Math.PI); g.stroke(); }
    for (const deg of [-60, -30, 0, 30, 60]) line(g, [[cx, cy], [cx + R * Math.sin(rad(deg)), cy - R * Math.cos(rad(deg))]]);
    line(g, [[cx - R, cy], [cx + R, cy]]);
    // the light (left) and its mirror direction (right)
    g.strokeStyle = "#e0a000"; g.lineWidth = 2;
    line(g, [[cx, cy], [cx - R * Math.sin(rad(state.theta)), cy - R * Math.cos(rad(state.theta))]]);
    g.setLineDash([4, 3]); g.strokeStyle = "#aaa"; g.lineWidth = 1;
    line(g, [[cx, cy], [cx + R * Math.sin(rad(state.theta)), cy - R * Math.cos(rad(state.theta))]]);
    g.setLineDash([]);
    g.strokeStyle = "#1e6edc"; g.lineWidth = 1.8;
    line(g, d.theta_v.map((t, i) => [cx + R * (ys[i] / top) * Math.sin(rad(t)), cy - R * (ys[i] / top) * Math.cos(rad(t))]));
    g.fillStyle = "#333"; g.font = "12px system-ui"; g.textAlign = "left";
    g.fillText(`max ${state.lobeMode === "f" ? "f" : "f cos θ_V"} = ${fmt(top, 3)} (outer circle)`, 6, 14);
    g.fillStyle = "#b07800"; g.fillText(`L at ${fmt(state.theta, 3)}°`, 6, 30);
  }

  drawLobe3d(g, W, H, d) {
    // f cos θ_V over the hemisphere, turned by yaw (about the normal) and pitch, drawn orthographically
    const top = Math.max(...d.fcos.flat().map((v) => v || 0)) || 1;
    const R = Math.min(W, H) * 0.42, cx = W / 2, cy = H * 0.62;
    const cy_ = Math.cos(rad(state.yaw)), sy = Math.sin(rad(state.yaw));
    const cp = Math.cos(rad(state.pitch)), sp = Math.sin(rad(state.pitch));
    const project = ([x, y, z]) => {
      const x1 = cy_ * x - sy * y, y1 = sy * x + cy_ * y;
      return [cx + R * x1, cy - R * (cp * z + sp * y1)];
    };
    const point = (i, j, r) => {
      const t = rad(d.theta_v[i]), p = rad(d.phi_v[j]);
      return [r * Math.sin(t) * Math.cos(p), r * Math.sin(t) * Math.sin(p), r * Math.cos(t)];
    };
    g.strokeStyle = "#ccc"; g.lineWidth = 1;
    line(g, Array.from({ length: 73 }, (_, k) => project([Math.cos(rad(5 * k)), Math.sin(rad(5 * k)), 0])));
    line(g, [project([0, 0, 0]), project([0, 0, 1])]);
    g.strokeStyle = "#e0a000"; g.lineWidth = 2;
    line(g, [project([0, 0, 0]), project([-Math.sin(rad(state.theta)), 0, Math.cos(rad(state.theta))])]);
    g.strokeStyle = "rgba(30, 110, 220, 0.75)"; g.lineWidth = 1;
    const r = (i, j) => (d.fcos[i][j] || 0) / top;
    for (let i = 0; i < d.theta_v.length; i++) line(g, d.phi_v.map((_, j) => project(point(i, j, r(i, j)))));
    for (let j = 0; j < d.phi_v.length - 1; j++) line(g, d.theta_v.map((_, i) => project(point(i, j, r(i, j)))));
    g.fillStyle = "#333"; g.font = "12px system-ui"; g.textAlign = "left";
    g.fillText(`max f cos θ_V = ${fmt(top, 3)} (unit radius); drag to turn`, 6, 14);
    g.fillStyle = "#b07800"; g.fillText(`L at ${fmt(state.theta, 3)}°`, 6, 30);
  }

  drawSlice(d) {
    const img = this.root.querySelector("img.slice");
    const cap = this.root.querySelector(".slice-caption");
    this.sliceCaption = this.sliceCaption || cap.innerHTML;
    this.root.querySelector(".slice-box").hidden = !d.png;
    if (d.png) { img.src = "data:image/png;base64," + d.png; cap.innerHTML = this.sliceCaption; }
    else { img.removeAttribute("src"); cap.textContent = d.reason; }
  }
}

// --- small drawing helpers -------------------------------------------------------------------------
const rad = (deg) => (deg * Math.PI) / 180;
function el(tag, props = {}) { return Object.assign(document.createElement(tag), props); }
function interval(p) {
  return `${p.open[0] ? "(" : "["}${p.range[0]}, ${p.range[1]}${p.open[1] || p.range[1] === "inf" ? ")" : "]"}`;
}
function line(g, pts) { g.beginPath(); pts.forEach(([x, y], i) => (i ? g.lineTo(x, y) : g.moveTo(x, y))); g.stroke(); }
function niceCeil(x) { const p = Math.pow(10, Math.floor(Math.log10(x))); return [1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10].map((k) => k * p).find((v) => v >= x); }
function ticks(ymax) { const step = niceCeil(ymax / 5); const out = []; for (let v = 0; v <= ymax + 1e-12; v += step) out.push(v); return out; }
function axes(g, W, H, m, xt, yt, px, py, xlabel, ylabel) {
  g.strokeStyle = "#888"; g.fillStyle = "#333"; g.lineWidth = 1; g.font = "11px system-ui";
  line(g, [[m.l, m.t], [m.l, H - m.b], [W - m.r, H - m.b]]);
  g.textAlign = "center";
  for (const t of xt) { line(g, [[px(t), H - m.b], [px(t), H - m.b + 4]]); g.fillText(String(t), px(t), H - m.b + 15); }
  g.fillText(xlabel, (m.l + W - m.r) / 2, H - 3);
  g.textAlign = "right";
  for (const v of yt) { line(g, [[m.l - 4, py(v)], [m.l, py(v)]]); g.fillText(fmt(v, 3), m.l - 6, py(v) + 4); }
  g.save(); g.translate(11, (m.t + H - m.b) / 2); g.rotate(-Math.PI / 2); g.textAlign = "center"; g.fillText(ylabel, 0, 0); g.restore();
}

// --- the URL: #theta=30&left=ggx&left.alpha=0.3&right=phong&right.n=20 -------------------------------
function writeHash() {
  const q = new URLSearchParams({ theta: state.theta });
  if (state.lobeMode !== "fcos") q.set("lobe", state.lobeMode);
  for (const side of SIDES) {
    const panel = state.panels[side];
    if (!panel) continue;
    q.set(side, panel.model.name);
    for (const [k, v] of Object.entries(panel.values)) q.set(`${side}.${k}`, v);
  }
  history.replaceState(null, "", "#" + q.toString());
}

function readHash() {
  const q = new URLSearchParams(location.hash.slice(1));
  const lobe = ["fcos", "f", "3d"].includes(q.get("lobe")) ? q.get("lobe") : null;
  const out = { theta: q.get("theta"), lobe, left: null, right: null };
  for (const side of SIDES) {
    if (!q.get(side)) continue;
    const values = {};
    for (const [k, v] of q.entries()) if (k.startsWith(side + ".")) values[k.slice(side.length + 1)] = v;
    out[side] = { name: q.get(side), values };
  }
  return out;
}

function showSide(side, name, values = {}) {
  const main = document.getElementById("panels");
  if (!name) {
    if (state.panels[side]) { state.panels[side].root.remove(); delete state.panels[side]; }
    for (const key of [...problems.keys()]) if (key.startsWith(side + ":")) setProblem(key, null);
    return;
  }
  if (!state.byName[name]) { setProblem(`${side}:model`, `${name}: not a registered model (brdfs models lists them)`); return; }
  setProblem(`${side}:model`, null);
  if (!state.panels[side]) { state.panels[side] = new Panel(side); main.append(state.panels[side].root); }
  if (side === "left" && state.panels.right) main.prepend(state.panels.left.root);
  state.panels[side].setModel(name, values);
  document.getElementById(`${side}-model`).value = name;
}

function setTheta(text) {
  const v = Number(text);
  if (!(v >= 0 && v <= 90)) { setProblem("theta", `θ_L = ${text}: the incidence angle must lie in [0, 90] degrees`); return; }
  setProblem("theta", null);
  state.theta = v;
  document.getElementById("theta").value = v;
  document.getElementById("theta-slider").value = v;
  writeHash();
  for (const panel of Object.values(state.panels)) panel.refresh(false);
}

async function start() {
  let response;
  try {
    response = await fetch("/api/models");
    state.catalogue = await response.json();
  } catch (err) {
    setProblem("start", `could not load the model list (${err.message})`);
    return;
  }
  for (const m of state.catalogue.models) state.byName[m.name] = m;
  for (const side of SIDES) {
    const select = document.getElementById(`${side}-model`);
    for (const m of state.catalogue.models) select.append(el("option", { value: m.name, textContent: m.name }));
    select.addEventListener("change", () => { showSide(side, select.value); writeHash(); });
  }
  document.getElementById("theta-slider").addEventListener("input", (e) => setTheta(e.target.value));
  document.getElementById("theta").addEventListener("change", (e) => setTheta(e.target.value));
  document.getElementById("lobe-mode").addEventListener("change", (e) => {
    const was3d = state.lobeMode === "3d";
    state.lobeMode = e.target.value;
    writeHash();
    for (const panel of Object.values(state.panels)) {
      if (was3d !== (state.lobeMode === "3d")) panel.requestLobe(); else panel.drawLobe();
    }
  });
  const wanted = readHash();
  if (wanted.theta !== null) setTheta(wanted.theta);
  if (wanted.lobe) { state.lobeMode = wanted.lobe; document.getElementById("lobe-mode").value = wanted.lobe; }
  showSide("left", wanted.left ? wanted.left.name : state.catalogue.models[0].name, wanted.left ? wanted.left.values : {});
  if (wanted.right) showSide("right", wanted.right.name, wanted.right.values);
  writeHash();
  window.explorer.ready = true;
}

window.addEventListener("hashchange", () => {
  const wanted = readHash();
  if (wanted.theta !== null && Number(wanted.theta) !== state.theta) setTheta(wanted.theta);
  if (wanted.left) showSide("left", wanted.left.name, wanted.left.values);
  showSide("right", wanted.right && wanted.right.name, wanted.right ? wanted.right.values : {});
});
document.addEventListener("DOMContentLoaded", start);
