/* "Try the model": the meta-model chapter's real-time force -> pose model in the reader's browser.
 *
 * A classic script (no modules, no workers, nothing fetched): the page carries the model as a
 * literal, window.MECHLIB_EXPLORER, written when the book is built from the chapter's record
 * (mechlib/pipeline/book/explorer.py). This file evaluates it with the operations, in the order,
 * of the plain-Python reference evaluator (mechlib/metamodels/evaluator.py: the Legendre
 * three-term recurrence), inverts it by Newton's method with its analytic Jacobian, and drives
 * the page (sliders, pose table, drawing, inverse form, timing). window.mechlibExplorer exposes
 * pose(forces), linearPose(forces), jacobian(forces) and inverse(target). The book loads this
 * file on every page; where there is no explorer it only defines those functions.
 */
(function () {
  "use strict";
  var NEWTON_TOL = 1e-12; // converged: |pose - target| <= NEWTON_TOL x range, every component
  var ACCEPT_TOL = 1e-9; // a Newton run that stalls within this x range still counts as converged
  var NEWTON_MAX_ITER = 50;
  var HALVINGS = 30; // halvings of a step that does not reduce the largest error
  var TIMING_WARMUP = 2000; // poses evaluated, untimed, before the page's timing loop, ...
  var TIMING_MS = 50; // ... which runs at least this long ...
  var TIMING_MAX_POSES = 1 << 18; // ... or this many poses
  var FORCE_PLACES = 4; // forces found by the inverse are shown to 1e-4 N
  // a force beyond the validated amplitude by less than half a shown digit is at it (Newton's
  // round-off would otherwise warn of 1.0000 N beyond +-1 N)
  var OUTSIDE_SLACK = 0.5 * Math.pow(10, -FORCE_PLACES);
  var TARGET_LIMIT = 2; // a typed target lies within this x the component's range (largest |value|
  // on the held-out runs): beyond it the polynomial is far outside what it was fitted on
  var cache = null;

  function load() {
    if (cache) return cache;
    var m = window.MECHLIB_EXPLORER;
    if (!m) throw new Error("no model on this page: window.MECHLIB_EXPLORER is not defined");
    var nin = m.inputs.length, nout = m.outputs.length, i, j, t;
    var raw = atob(m.coef_b64), view = new DataView(new ArrayBuffer(raw.length));
    for (i = 0; i < raw.length; i++) view.setUint8(i, raw.charCodeAt(i));
    var coef = new Float64Array(raw.length / 8);
    for (i = 0; i < coef.length; i++) coef[i] = view.getFloat64(8 * i, true);
    var terms = m.exponents.length / nin, deg = 0;
    for (i = 0; i < m.exponents.length; i++) deg = Math.max(deg, +m.exponents[i]);
    if (coef.length !== terms * nout) {
      throw new Error("the model has " + coef.length + " coefficients, expected " + terms * nout);
    }
    // per term: the flat basis indices (input x (deg + 1) + k) of its non-zero exponents; a zero
    // exponent's factor is exactly 1.0, so leaving it out changes no bit of the product
    var idx = [], inp = [], start = [0];
    for (t = 0; t < terms; t++) {
      for (j = 0; j < nin; j++) {
        var k = +m.exponents[t * nin + j];
        if (k) { idx.push(j * (deg + 1) + k); inp.push(j); }
      }
      start.push(idx.length);
    }
    var d1 = deg + 1;
    cache = {
      m: m, nin: nin, nout: nout, terms: terms, deg: deg, coef: coef, amp: m.amplitude_n,
      idx: Int32Array.from(idx), inp: Int32Array.from(inp), start: Int32Array.from(start),
      b: new Float64Array(nin * d1), db: new Float64Array(nin * d1),
    };
    return cache;
  }

  // b[i (deg+1) + k] = sqrt(2k+1) P_k(u_i), u_i = f_i / amplitude (and db = d b / d f_i)
  function basis(mo, f, deriv) {
    var d1 = mo.deg + 1, b = mo.b, db = mo.db;
    for (var i = 0; i < mo.nin; i++) {
      var u = f[i] / mo.amp, o = i * d1, pm = 1.0, p = f[i] / mo.amp, dm = 0.0, dp = 1.0;
      b[o] = 1.0; // sqrt(1) P_0
      if (deriv) db[o] = 0.0;
      if (mo.deg >= 1) {
        b[o + 1] = Math.sqrt(3) * p;
        if (deriv) db[o + 1] = Math.sqrt(3) * dp / mo.amp;
      }
      for (var k = 1; k < mo.deg; k++) {
        var pn = ((2 * k + 1) * u * p - k * pm) / (k + 1);
        if (deriv) { var dn = dm + (2 * k + 1) * p; dm = dp; dp = dn; }
        pm = p; p = pn;
        b[o + k + 1] = Math.sqrt(2 * k + 3) * p;
        if (deriv) db[o + k + 1] = Math.sqrt(2 * k + 3) * dp / mo.amp;
      }
    }
  }

  function evaluate(mo, out) {
    var c = mo.coef, b = mo.b, idx = mo.idx, start = mo.start, nout = mo.nout, o;
    for (o = 0; o < nout; o++) out[o] = 0.0;
    for (var t = 0; t < mo.terms; t++) {
      var term = 1.0, row = t * nout;
      for (var s = start[t]; s < start[t + 1]; s++) term *= b[idx[s]];
      for (o = 0; o < nout; o++) out[o] = out[o] + term * c[row + o];
    }
  }

  function jacobianInto(mo, J) { // J[o nin + i] = d pose_o / d f_i, after basis(mo, f, true)
    var c = mo.coef, b = mo.b, db = mo.db, idx = mo.idx, start = mo.start, nin = mo.nin;
    var nout = mo.nout, o;
    for (o = 0; o < J.length; o++) J[o] = 0.0;
    for (var t = 0; t < mo.terms; t++) {
      for (var a = start[t]; a < start[t + 1]; a++) {
        var g = db[idx[a]];
        for (var s = start[t]; s < start[t + 1]; s++) if (s !== a) g *= b[idx[s]];
        var i = mo.inp[a], row = t * nout;
        for (o = 0; o < nout; o++) J[o * nin + i] += g * c[row + o];
      }
    }
  }

  // values as numbers (typed text too, with "\u2212" as minus), each finite and, when limits are
  // given, within +-limits[i]; else an Error naming the entry, its value and what is allowed
  function checked(name, values, labels, limits, units) {
    if (!values || values.length !== labels.length) {
      throw new Error(name + " must have " + labels.length + " entries (" + labels.join(", ") +
        "), got " + (values ? values.length : values));
    }
    var out = new Float64Array(labels.length);
    for (var i = 0; i < labels.length; i++) {
      var v = typeof values[i] === "string" && values[i].trim() !== "" ?
        Number(values[i].trim().replace(/\u2212/g, "-")) : values[i];
      var allowed = limits ? "a number within \u00b1" + +limits[i].toPrecision(4) + " " + units[i] :
        "a finite number";
      if (typeof v !== "number" || !isFinite(v) || (limits && Math.abs(v) > limits[i])) {
        throw new Error(labels[i] + " must be " + allowed + ", got '" + values[i] + "'");
      }
      out[i] = v;
    }
    return out;
  }

  function labels(names, units) {
    return names.map(function (n, i) { return n + " [" + (units ? units[i] : "N") + "]"; });
  }

  function pose(forces) {
    var mo = load(), f = checked("forces", forces, labels(mo.m.inputs));
    var out = new Float64Array(mo.nout);
    basis(mo, f, false);
    evaluate(mo, out);
    return Array.from(out);
  }

  function jacobian(forces) {
    var mo = load(), f = checked("forces", forces, labels(mo.m.inputs));
    var J = new Float64Array(mo.nout * mo.nin);
    basis(mo, f, true);
    jacobianInto(mo, J);
    var rows = [];
    for (var o = 0, n = mo.nin; o < mo.nout; o++) rows.push(Array.from(J.slice(o * n, o * n + n)));
    return rows;
  }

  function linearPose(forces) {
    var mo = load(), f = checked("forces", forces, labels(mo.m.inputs));
    return mo.m.S_T.map(function (row) {
      var s = 0.0;
      for (var i = 0; i < row.length; i++) s += row[i] * f[i];
      return s;
    });
  }

  // x of A x = r (n x n, row-major): Gaussian elimination, partial pivoting; null when singular
  function solve(A, r, n) {
    var a = Float64Array.from(A), x = Float64Array.from(r), i, j, k;
    for (k = 0; k < n; k++) {
      var p = k;
      for (i = k + 1; i < n; i++) if (Math.abs(a[i * n + k]) > Math.abs(a[p * n + k])) p = i;
      if (!(Math.abs(a[p * n + k]) > 0)) return null;
      if (p !== k) {
        for (j = 0; j < n; j++) { var w = a[k*n + j]; a[k*n + j] = a[p*n + j]; a[p*n + j] = w; }
        var q = x[k]; x[k] = x[p]; x[p] = q;
      }
      for (i = k + 1; i < n; i++) {
        var l = a[i * n + k] / a[k * n + k];
        for (j = k; j < n; j++) a[i * n + j] -= l * a[k * n + j];
        x[i] -= l * x[k];
      }
    }
    for (k = n - 1; k >= 0; k--) {
      for (j = k + 1; j < n; j++) x[k] -= a[k * n + j] * x[j];
      x[k] /= a[k * n + k];
    }
    return x;
  }

  // the largest |pose - target| / range, and the scaled residual (target - pose) / range
  function miss(mo, f, y, out, scaled) {
    basis(mo, f, false);
    evaluate(mo, out);
    var worst = 0.0;
    for (var o = 0; o < mo.nout; o++) {
      scaled[o] = (y[o] - out[o]) / mo.m.range[o];
      worst = Math.max(worst, Math.abs(scaled[o]));
    }
    return worst;
  }

  function inverse(target) {
    var mo = load(), n = mo.nin, o, i;
    if (mo.nout !== n) throw new Error("the inverse needs as many forces as pose components");
    var limits = mo.m.range.map(function (r) { return TARGET_LIMIT * r; });
    var y = checked("target", target, labels(mo.m.outputs, mo.m.units), limits, mo.m.units);
    var x = new Float64Array(n), out = new Float64Array(n), r = new Float64Array(n);
    var J = new Float64Array(n * n), xn = new Float64Array(n), rn = new Float64Array(n);
    var err = miss(mo, x, y, out, r), iterations = 0, stalled = false;
    while (err > NEWTON_TOL && iterations < NEWTON_MAX_ITER) {
      basis(mo, x, true);
      jacobianInto(mo, J);
      for (o = 0; o < n; o++) for (i = 0; i < n; i++) J[o * n + i] /= mo.m.range[o];
      var dx = solve(J, r, n), lam = 1.0, better = false;
      if (!dx) { stalled = true; break; }
      for (var h = 0; h <= HALVINGS && !better; h++, lam /= 2) {
        for (i = 0; i < n; i++) xn[i] = x[i] + lam * dx[i];
        var e = miss(mo, xn, y, out, rn);
        if (e < err) { better = true; err = e; x.set(xn); r.set(rn); }
      }
      iterations++;
      if (!better) { stalled = true; break; }
    }
    var largest = 0.0;
    for (i = 0; i < n; i++) largest = Math.max(largest, Math.abs(x[i]));
    var reached = pose(Array.from(x));
    return {
      forces: Array.from(x), pose: reached, target: Array.from(y),
      difference: reached.map(function (p, k) { return p - y[k]; }),
      error: err, iterations: iterations, stalled: stalled,
      converged: err <= ACCEPT_TOL, largest: largest,
      outside: largest > mo.amp + OUTSIDE_SLACK,
    };
  }

  var api = {pose: pose, linearPose: linearPose, jacobian: jacobian, inverse: inverse};
  window.mechlibExplorer = api;

  // --- the page ---------------------------------------------------------------------------------
  function fmt(v, places) {
    var s = v.toFixed(places);
    if (Number(s) === 0) s = (0).toFixed(places);
    return s.replace("-", "\u2212");
  }

  function byId(id) { return document.getElementById(id); }
  function setText(id, text) { byId(id).textContent = text; }

  function moved(d, poseV, mag) { // displaced outline points, [x, y, z] mm
    var t = [poseV[0] * 1e-3, poseV[1] * 1e-3, poseV[2] * 1e-3];
    var th = [poseV[3] * 1e-6, poseV[4] * 1e-6, poseV[5] * 1e-6];
    return d.map(function (p) {
      return [
        p[0] + mag * (t[0] - th[2] * p[1]),
        p[1] + mag * (t[1] + th[2] * p[0]),
        mag * (t[2] + th[0] * p[1] - th[1] * p[0]),
      ];
    });
  }

  function arrowPath(x0, y0, x1, y1) {
    var dx = x1 - x0, dy = y1 - y0, len = Math.sqrt(dx * dx + dy * dy);
    if (len < 1e-6) return "";
    var ux = dx / len, uy = dy / len, hl = Math.min(3, 0.5 * len), hw = 0.45 * hl;
    return "M" + x0.toFixed(2) + " " + y0.toFixed(2) + "L" + x1.toFixed(2) + " " + y1.toFixed(2) +
      "M" + (x1 - hl * ux + hw * uy).toFixed(2) + " " + (y1 - hl * uy - hw * ux).toFixed(2) +
      "L" + x1.toFixed(2) + " " + y1.toFixed(2) +
      "L" + (x1 - hl * ux - hw * uy).toFixed(2) + " " + (y1 - hl * uy + hw * ux).toFixed(2);
  }

  function draw(m, forces, poseV) {
    var dr = m.drawing;
    dr.views.forEach(function (v, k) {
      var mag = dr.magnification[v.magnification];
      var pts = moved(dr.outline_mm, poseV, mag).map(function (p) {
        return p[v.h].toFixed(3) + "," + p[v.v].toFixed(3);
      });
      byId("mx-body-" + k).setAttribute("points", pts.join(" "));
      var at = moved(dr.actuators_mm, poseV, mag), d = "";
      v.forces.forEach(function (i) {
        var dir = dr.directions[i], s = dr.arrow_mm_per_n * forces[i];
        var a = at[i];
        d += arrowPath(a[v.h], a[v.v], a[v.h] + s * dir[v.h], a[v.v] + s * dir[v.v]);
      });
      byId("mx-force-" + k).setAttribute("d", d);
    });
  }

  function forcesOf(m) {
    return m.inputs.map(function (_, i) { return +byId("mx-f" + i).value; });
  }

  function update() {
    var m = load().m, f = forcesOf(m), p = pose(f), q = linearPose(f);
    var places = Math.max(0, -Math.floor(Math.log10(m.amplitude_n / 100)));
    f.forEach(function (v, i) { setText("mx-f" + i + "-out", fmt(v, places) + " N"); });
    p.forEach(function (v, o) {
      var d = m.decimals[o];
      setText("mx-nl-" + o, fmt(v, d));
      setText("mx-lin-" + o, fmt(q[o], d));
      setText("mx-diff-" + o, fmt(v - q[o], d));
    });
    draw(m, f, p);
    return p;
  }

  function timing() { // measured here, in the reader's browser: poses one after another
    var m = load().m, n = m.inputs.length, set = [], seed = 12345, i;
    for (i = 0; i < 64; i++) {
      var f = [];
      for (var j = 0; j < n; j++) {
        seed = (seed * 1103515245 + 12345) % 2147483648;
        f.push(m.amplitude_n * (2 * seed / 2147483648 - 1));
      }
      set.push(f);
    }
    var count = 256, ms = 0, sink = 0;
    for (i = 0; i < TIMING_WARMUP; i++) sink += pose(set[i & 63])[0]; // the JIT compiles first
    while (true) {
      var t0 = performance.now();
      for (i = 0; i < count; i++) sink += pose(set[i & 63])[0];
      ms = performance.now() - t0;
      if (ms >= TIMING_MS || count >= TIMING_MAX_POSES) break;
      count *= 2;
    }
    if (!(ms > 0) || !isFinite(sink)) {
      setText("mx-timing", "A pose took too little time to measure in your browser (" + count +
        " poses in under the clock's resolution).");
      return;
    }
    var us = 1000 * ms / count;
    setText("mx-timing", "Measured in your browser when this page opened: " +
      us.toPrecision(2) + " \u00b5s a pose (" + count + " poses one after another, " +
      ms.toFixed(0) + " ms).");
  }

  function table(head, rows) { // a <table>: a header row, then rows whose first cell is a header
    var t = document.createElement("table");
    t.className = "table";
    [head].concat(rows).forEach(function (cells, r) {
      var tr = t.appendChild(document.createElement("tr"));
      cells.forEach(function (text, c) {
        tr.appendChild(document.createElement(r === 0 || c === 0 ? "th" : "td")).textContent = text;
      });
    });
    return t;
  }

  function showInverse(m) {
    var box = byId("mx-inverse-out"), res, places = FORCE_PLACES;
    var typed = m.outputs.map(function (_, o) { return byId("mx-t" + o).value; });
    box.textContent = "";
    var note = box.appendChild(document.createElement("p"));
    try {
      res = inverse(typed);
    } catch (err) {
      note.className = "mx-error";
      note.textContent = err.message;
      return;
    }
    if (!res.converged) {
      note.className = "mx-error";
      note.textContent = "Newton's method found no forces that reach this pose (after " +
        res.iterations + " steps it still misses by " + (100 * res.error).toPrecision(2) +
        " % of full scale); the closest forces it found are shown.";
    } else if (res.outside) {
      note.className = "mx-warn";
      note.textContent = "This pose needs a force beyond \u00b1" + m.amplitude_n + " N (largest " +
        fmt(res.largest, places) + " N): outside the range the model was validated on, so the " +
        "forces below are the polynomial's extrapolation.";
    } else {
      note.textContent = "Forces found in " + res.iterations + " Newton steps, all within \u00b1" +
        m.amplitude_n + " N.";
    }
    box.appendChild(table(["force"].concat(m.inputs.map(function (n) { return n + " [N]"; })),
      [["found"].concat(res.forces.map(function (v) { return fmt(v, places); }))]));
    box.appendChild(table(
      ["pose component", "unit", "target", "model's pose for the forces found",
        "model's pose \u2212 target"],
      m.outputs.map(function (name, o) {
        var d = m.decimals[o];
        return [name, m.units[o], fmt(res.target[o], d), fmt(res.pose[o], d),
          res.difference[o].toExponential(1).replace(/-/g, "\u2212")];
      })));
  }

  function init() {
    if (!byId("mx") || !window.MECHLIB_EXPLORER) return;
    var m = load().m;
    document.documentElement.classList.add("mx-on");
    m.inputs.forEach(function (_, i) { byId("mx-f" + i).addEventListener("input", update); });
    byId("mx-reset").addEventListener("click", function () {
      m.inputs.forEach(function (_, i) { byId("mx-f" + i).value = "0"; });
      update();
    });
    byId("mx-copy").addEventListener("click", function () {
      update().forEach(function (v, o) { byId("mx-t" + o).value = fmt(v, m.decimals[o]); });
    });
    byId("mx-inverse").addEventListener("submit", function (ev) {
      ev.preventDefault();
      showInverse(m);
    });
    update();
    timing();
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init);
  else init();
})();
