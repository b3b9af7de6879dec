// pkm HTML report: draws the figures from the embedded report data (schema pkm.report/1,
// docs/report.md) with uPlot (MIT licence, inlined). Each <figure data-plot-id> gets one chart.
/* global uPlot */
(function () {
  "use strict";

  // Series colours (colour-blind safe, Okabe-Ito): first "before", second "after", ...
  const COLOURS = ["#d55e00", "#0072b2", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000"];
  // Viridis stops for marker colour by value (scatter "value").
  const VIRIDIS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const HEIGHT = 340;
  const POLAR_SIZE = 460;

  const colour = (i) => COLOURS[i % COLOURS.length];

  function viridis(t) {
    const s = Math.min(Math.max(t, 0), 1) * (VIRIDIS.length - 1);
    const i = Math.min(Math.floor(s), VIRIDIS.length - 2);
    const f = s - i;
    const c = VIRIDIS[i].map((a, k) => Math.round(a + f * (VIRIDIS[i + 1][k] - a)));
    return `rgb(${c[0]},${c[1]},${c[2]})`;
  }

  // The smallest 1, 2 or 5 times a power of ten that is >= v (v > 0).
  function niceCeil(v) {
    const p = Math.pow(10, Math.floor(Math.log10(v)));
    for (const m of [1, 2, 5, 10]) if (m * p >= v * (1 - 1e-12)) return m * p;
    return 10 * p;
  }

  const fmt = (v) => Number(v.toPrecision(6)).toString();

  function chartWidth(el) {
    return Math.max(320, Math.min(el.clientWidth || 800, 900));
  }

  // Tick labels as plain numbers (no thousands separators), at most 10 significant digits.
  const ticks = (u, splits) => splits.map((v) => (v == null ? "" : String(Number(v.toPrecision(10)))));

  // Room for the y tick labels (~7 px per character at the 12 px axis font) and the axis label.
  const ySize = (u, values) => {
    const chars = values && values.length ? Math.max(...values.map((v) => String(v).length)) : 4;
    return 34 + 7 * chars;
  };

  function axes(plot) {
    return [
      { label: plot.x_label || "", values: ticks },
      { label: plot.y_label || "", values: ticks, size: ySize },
    ];
  }

  // line: x ascending; series with different x are joined on the union of x (gaps spanned). A
  // series with "lower" and "upper" gets a shaded band between them (e.g. value -/+ U), drawn as two
  // thin dashed series after the plain ones.
  function linePlot(plot, el) {
    const columns = plot.series.map((s) => [s.x, s.y]);
    const series = [{ label: plot.x_label || "x" }].concat(
      plot.series.map((s, i) => ({
        label: s.label,
        stroke: colour(i),
        width: 2,
        spanGaps: true,
        points: { show: true, size: 6, fill: colour(i) },
      }))
    );
    const bands = [];
    plot.series.forEach((s, i) => {
      if (!Array.isArray(s.lower) || !Array.isArray(s.upper)) return;
      const edge = (label) => ({ label, stroke: colour(i), width: 1, dash: [4, 4], spanGaps: true,
        points: { show: false } });
      columns.push([s.x, s.upper], [s.x, s.lower]);
      series.push(edge(`${s.label} upper`), edge(`${s.label} lower`));
      bands.push({ series: [series.length - 2, series.length - 1], fill: `${colour(i)}33` });
    });
    const data = uPlot.join(columns);
    const opts = { width: chartWidth(el), height: HEIGHT, scales: { x: { time: false } },
      axes: axes(plot), series };
    if (bands.length > 0) opts.bands = bands;
    return new uPlot(opts, data, el);
  }

  // bar: x = categories; series drawn as grouped bars from zero.
  function barPaths(group, groups) {
    return (u, sidx, i0, i1) => {
      const fill = new Path2D();
      const xs = u.data[0];
      const ys = u.data[sidx];
      const step = Math.abs(u.valToPos(1, "x", true) - u.valToPos(0, "x", true));
      const groupWidth = 0.8 * step;
      const w = groupWidth / groups;
      const y0 = u.valToPos(0, "y", true);
      for (let i = i0; i <= i1; i++) {
        if (ys[i] == null) continue;
        const left = u.valToPos(xs[i], "x", true) - groupWidth / 2 + group * w;
        const y = u.valToPos(ys[i], "y", true);
        fill.rect(left, Math.min(y, y0), w * 0.92, Math.max(Math.abs(y - y0), 1));
      }
      return { stroke: fill, fill };
    };
  }

  function barPlot(plot, el) {
    const cats = plot.categories || plot.series[0].categories;
    const index = cats.map((_, i) => i);
    const data = [index].concat(
      plot.series.map((s) => {
        const own = s.categories || cats;
        return cats.map((c) => {
          const k = own.indexOf(c);
          return k < 0 ? null : s.y[k];
        });
      })
    );
    const series = [{ label: plot.x_label || "category", value: (u, v) => (v == null ? "" : cats[v]) }]
      .concat(plot.series.map((s, i) => ({
        label: s.label,
        stroke: colour(i),
        fill: colour(i),
        width: 1,
        paths: barPaths(i, plot.series.length),
        points: { show: false },
      })));
    const yRange = (u, lo, hi) => {
      const a = Math.min(0, lo);
      const b = Math.max(0, hi);
      const pad = 0.08 * (b - a || 1);
      return [a < 0 ? a - pad : 0, b > 0 ? b + pad : 0];
    };
    const opts = {
      width: chartWidth(el), height: HEIGHT,
      scales: { x: { time: false, range: [-0.5, cats.length - 0.5] }, y: { range: yRange } },
      axes: [
        { label: plot.x_label || "", splits: () => index,
          values: (u, splits) => splits.map((v) => cats[v] ?? "") },
        { label: plot.y_label || "", values: ticks, size: ySize },
      ],
      series,
    };
    return new uPlot(opts, data, el);
  }

  // Padding of 5 % around the data range (markers must not sit on the frame).
  const padded = (u, lo, hi) => {
    const pad = 0.05 * (hi - lo || Math.abs(hi) || 1);
    return [lo - pad, hi + pad];
  };

  // scatter: markers only, own x per series (uPlot mode 2), drawn by the draw hook; an optional
  // per-series "value" colours that series' markers (viridis, with a colour scale below).
  function scatterPlot(plot, el) {
    const coloured = plot.series.filter((s) => Array.isArray(s.value));
    let lo = Infinity;
    let hi = -Infinity;
    for (const s of coloured) for (const v of s.value) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    const span = hi > lo ? hi - lo : 1;
    const markerColour = (s, i) => (Array.isArray(s.value) ? viridis(0.5) : colour(i));
    const drawMarkers = (u) => {
      const ctx = u.ctx;
      ctx.save();
      ctx.beginPath();
      ctx.rect(u.bbox.left, u.bbox.top, u.bbox.width, u.bbox.height);
      ctx.clip();
      const r = 3.5 * devicePixelRatio;
      plot.series.forEach((s, k) => {
        if (!u.series[k + 1].show) return;
        for (let i = 0; i < s.x.length; i++) {
          ctx.fillStyle = Array.isArray(s.value) ? viridis((s.value[i] - lo) / span) : colour(k);
          ctx.beginPath();
          ctx.arc(u.valToPos(s.x[i], "x", true), u.valToPos(s.y[i], "y", true), r, 0, 2 * Math.PI);
          ctx.fill();
        }
      });
      ctx.restore();
    };
    const series = [{}].concat(plot.series.map((s, i) => ({
      label: s.label,
      stroke: markerColour(s, i),
      fill: markerColour(s, i),
      paths: () => null,
      points: { show: false },
    })));
    const opts = {
      mode: 2, width: chartWidth(el), height: HEIGHT,
      legend: { live: false },
      cursor: { drag: { x: false, y: false } },
      scales: { x: { time: false, range: padded }, y: { range: padded } },
      axes: axes(plot), series,
      hooks: { draw: [drawMarkers] },
    };
    const u = new uPlot(opts, [null].concat(plot.series.map((s) => [s.x, s.y])), el);
    if (coloured.length > 0) {
      const bar = document.createElement("div");
      bar.className = "colour-scale";
      bar.innerHTML = '<span class="lo"></span><span class="ramp"></span><span class="hi"></span>';
      bar.querySelector(".lo").textContent = fmt(lo);
      bar.querySelector(".hi").textContent = fmt(hi);
      bar.querySelector(".ramp").style.background =
        `linear-gradient(to right, ${VIRIDIS.map((_, i) => viridis(i / (VIRIDIS.length - 1))).join(",")})`;
      el.appendChild(bar);
    }
    return u;
  }

  // polar: roundness plot. x = angle (degrees), y = radial deviation; drawn as the x/y trace of
  // radius R0 + k * deviation around a base circle R0 = 1 (dashed), equal aspect.
  function polarPlot(plot, el) {
    let maxAbs = 0;
    for (const s of plot.series) for (const v of s.y) maxAbs = Math.max(maxAbs, Math.abs(v));
    const nice = maxAbs > 0 ? niceCeil(maxAbs) : 1;
    const k = 0.5 / nice; // +-nice maps to radius 1 +- 0.5
    const L = 1.85;
    // The deviation unit: the y label's "(unit)", mm by default (schema pkm.report/1).
    const unitMatch = /\(([^()]+)\)\s*$/.exec(plot.y_label || "");
    const unit = unitMatch ? unitMatch[1] : "mm";
    const trace = (s) => {
      const xs = [];
      const ys = [];
      s.x.forEach((deg, i) => {
        const r = 1 + k * s.y[i];
        const t = (deg * Math.PI) / 180;
        xs.push(r * Math.cos(t));
        ys.push(r * Math.sin(t));
      });
      // Close the curve when the angles cover the full circle.
      const n = s.x.length;
      if (n > 2) {
        const span = Math.max(...s.x) - Math.min(...s.x);
        if (span + 1.5 * (span / (n - 1)) >= 360) { xs.push(xs[0]); ys.push(ys[0]); }
      }
      return [xs, ys];
    };
    const grid = (u) => {
      const ctx = u.ctx;
      const cx = u.valToPos(0, "x", true);
      const cy = u.valToPos(0, "y", true);
      const px = (r) => Math.abs(u.valToPos(r, "x", true) - cx);
      const dpr = devicePixelRatio;
      ctx.save();
      ctx.font = `${11 * dpr}px sans-serif`;
      ctx.fillStyle = "#444";
      ctx.lineWidth = dpr;
      for (const f of [-1, -0.5, 0, 0.5, 1]) {
        ctx.strokeStyle = f === 0 ? "#555" : "#ccc";
        ctx.setLineDash(f === 0 ? [6 * dpr, 4 * dpr] : []);
        ctx.beginPath();
        ctx.arc(cx, cy, px(1 + 0.5 * f), 0, 2 * Math.PI);
        ctx.stroke();
        const label = f === 0 ? "0" : `${f > 0 ? "+" : "\u2212"}${fmt(Math.abs(f) * nice)}`;
        ctx.fillText(label, cx + 3 * dpr, cy - px(1 + 0.5 * f) - 3 * dpr);
      }
      ctx.setLineDash([]);
      ctx.strokeStyle = "#e3e3e3";
      ctx.textAlign = "center";
      ctx.textBaseline = "middle";
      for (let a = 0; a < 360; a += 30) {
        const t = (a * Math.PI) / 180;
        ctx.beginPath();
        ctx.moveTo(cx + px(0.4) * Math.cos(t), cy - px(0.4) * Math.sin(t));
        ctx.lineTo(cx + px(1.55) * Math.cos(t), cy - px(1.55) * Math.sin(t));
        ctx.stroke();
        ctx.fillText(`${a}\u00b0`, cx + px(1.7) * Math.cos(t), cy - px(1.7) * Math.sin(t));
      }
      ctx.restore();
    };
    const series = [{}].concat(plot.series.map((s, i) => ({
      label: s.label,
      stroke: colour(i),
      width: 2,
      paths: uPlot.paths.linear(),
      points: { show: false },
    })));
    const size = Math.min(chartWidth(el), POLAR_SIZE);
    const opts = {
      mode: 2, width: size, height: size,
      legend: { live: false },
      cursor: { show: false },
      scales: { x: { time: false, range: [-L, L] }, y: { range: [-L, L] } },
      axes: [{ show: false }, { show: false }],
      series,
      hooks: { drawAxes: [grid] },
    };
    const u = new uPlot(opts, [null].concat(plot.series.map(trace)), el);
    const note = document.createElement("p");
    note.className = "polar-scale";
    note.textContent = `${plot.y_label || "Radial deviation"} around the base circle (dashed); ` +
      `rings every ${fmt(nice / 2)} ${unit} (\u00b1${fmt(nice)} ${unit} at the inner and outer ring).`;
    el.appendChild(note);
    return u;
  }

  const BUILDERS = { line: linePlot, bar: barPlot, scatter: scatterPlot, polar: polarPlot };

  function main() {
    const data = JSON.parse(document.getElementById("pkm-report-data").textContent);
    const charts = [];
    let failures = 0;
    for (const plot of data.plots) {
      const fig = document.querySelector(`figure[data-plot-id="${CSS.escape(plot.id)}"]`);
      if (!fig) {
        console.error(`pkm report: no figure for plot ${plot.id}`);
        failures++;
        continue;
      }
      const el = fig.querySelector(".chart");
      try {
        charts.push({ plot, el, u: BUILDERS[plot.kind](plot, el) });
      } catch (e) {
        failures++;
        el.textContent = `This figure could not be drawn: ${e}`;
        console.error(`pkm report: plot ${plot.id}: ${e && e.stack ? e.stack : e}`);
      }
    }
    let pending = 0;
    window.addEventListener("resize", () => {
      clearTimeout(pending);
      pending = setTimeout(() => {
        for (const c of charts) {
          const w = chartWidth(c.el);
          if (c.plot.kind === "polar") c.u.setSize({ width: Math.min(w, POLAR_SIZE), height: Math.min(w, POLAR_SIZE) });
          else c.u.setSize({ width: w, height: HEIGHT });
        }
      }, 150);
    });
    document.body.dataset.rendered = failures === 0 ? "ok" : "failed";
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", main);
  else main();
})();
