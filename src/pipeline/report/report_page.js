// report.html's page: reads the data the program embedded (element "sm-data" and the base64
// blocks "b-<id>"), draws the plots, the histogram and the tables, and starts the 3D player
// (window.SeqmassagePlayer, bundled from web/ when the build had it). Every string from the data
// reaches the page as text (textContent, createTextNode), never as markup. ASCII only: the build
// embeds this file as a C++ raw string.
(function () {
  "use strict";
  var SVG = "http://www.w3.org/2000/svg";
  var BEFORE = "#c8553d", AFTER = "#2a6fbb";
  var data = JSON.parse(document.getElementById("sm-data").textContent);
  var app = document.getElementById("app");

  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined && text !== null) e.textContent = String(text);
    return e;
  }
  function svg(tag, attrs) {
    var e = document.createElementNS(SVG, tag);
    for (var k in attrs) if (Object.prototype.hasOwnProperty.call(attrs, k)) e.setAttribute(k, String(attrs[k]));
    return e;
  }
  function section(title, id) {
    var s = el("section");
    if (id) s.id = id;
    s.appendChild(el("h2", null, title));
    app.appendChild(s);
    return s;
  }
  function fmt(x) {
    if (typeof x !== "number" || !isFinite(x)) return String(x);
    if (x === 0) return "0";
    var a = Math.abs(x);
    return a >= 1e4 || a < 1e-3 ? x.toExponential(3) : String(Number(x.toPrecision(4)));
  }

  // RFC 4180 CSV (summary.csv as written): quoted fields, doubled quotes, no trailing row.
  function parseCsv(text) {
    var rows = [], row = [], field = "", i = 0, quoted = false;
    while (i < text.length) {
      var c = text[i];
      if (quoted) {
        if (c === '"' && text[i + 1] === '"') { field += '"'; i += 2; continue; }
        if (c === '"') { quoted = false; i++; continue; }
        field += c; i++; continue;
      }
      if (c === '"') { quoted = true; i++; continue; }
      if (c === ",") { row.push(field); field = ""; i++; continue; }
      if (c === "\n") { row.push(field); rows.push(row); row = []; field = ""; i++; continue; }
      if (c === "\r") { i++; continue; }
      field += c; i++;
    }
    if (field !== "" || row.length) { row.push(field); rows.push(row); }
    return rows;
  }
  function num(s) {
    if (s === "inf") return Infinity;
    if (s === "-inf") return -Infinity;
    if (s === "nan" || s === "") return NaN;
    return Number(s);
  }

  var csv = parseCsv(data.summary_csv || "");
  var columns = csv.length ? csv[0] : [];
  var rows = csv.slice(1);
  function column(name) {
    var k = columns.indexOf(name);
    return rows.map(function (r) { return k < 0 ? NaN : num(r[k]); });
  }
  function textColumn(name) {
    var k = columns.indexOf(name);
    return rows.map(function (r) { return k < 0 ? "" : r[k]; });
  }
  var frameIndex = column("frame"), status = textColumn("status"), files = textColumn("file");
  var repaired = {};
  (data.warnings || []).forEach(function (w) {
    var m = /^frame (\d+) .*fold repair/.exec(w);
    if (m) repaired[Number(m[1])] = true;
  });

  // --- Header.
  var header = el("header");
  header.appendChild(el("h1", null, data.title));
  var failed = status.filter(function (s) { return s === "failed"; }).length;
  header.appendChild(el("p", "lead", data.kind === "mesh" ?
    (data.warnings || []).length + " warnings. Left: the mesh as loaded; right: the output." :
    rows.length + " frames, " + failed + " failed, " + (data.warnings || []).length +
    " warnings. Left: the input; right: the corrected frames."));
  app.appendChild(header);

  // --- Player.
  var cursors = [];
  var playerSection = section("Player", "player");
  var player = null;
  if (data.player && window.SeqmassagePlayer) {
    var blocks = function (id) {
      var e = document.getElementById("b-" + id);
      var s = atob(e.textContent);
      var bytes = new Uint8Array(s.length);
      for (var i = 0; i < s.length; i++) bytes[i] = s.charCodeAt(i);
      return bytes.buffer;
    };
    var marks = {};
    data.player.frames.forEach(function (f, k) {
      var r = frameIndex.indexOf(f);
      if (r >= 0 && status[r] === "failed") marks[k] = "failed";
      else if (repaired[f]) marks[k] = "repaired";
    });
    var names = data.player.frames.map(function (f) {
      var r = frameIndex.indexOf(f);
      return r >= 0 ? files[r] : "";
    });
    try {
      player = window.SeqmassagePlayer.create(playerSection, {
        player: data.player, fps: data.fps, names: names, marks: marks, blocks: blocks,
        onFrame: function (frame) { cursors.forEach(function (c) { c(frame); }); }
      });
    } catch (e) {
      playerSection.appendChild(el("p", "note", "The 3D player could not start: " + e.message));
    }
    if (data.player.frames.length < data.player.frames_total)
      playerSection.appendChild(el("p", "note", "The player keeps " + data.player.frames.length +
        " evenly spaced frames of " + data.player.frames_total + " to stay within output.html_max_mb; " +
        "the plots and the table have every frame."));
  } else {
    playerSection.appendChild(el("p", "note", "No 3D player: " +
      (data.player_missing || data.player_note || "this page has no player data") + "."));
  }

  // --- Line plots, one point per frame.
  function linePlot(parent, title, series, yLabel) {
    var W = 640, H = 260, L = 64, R = 12, T = 24, B = 36;
    var fig = el("figure", "plot");
    var box = svg("svg", { viewBox: "0 0 " + W + " " + H, role: "img", "class": "chart" });
    var xs = frameIndex, x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
    if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
    var y1 = 0;
    series.forEach(function (s) { s.values.forEach(function (v) { if (isFinite(v)) y1 = Math.max(y1, v); }); });
    if (!(y1 > 0)) y1 = 1;
    var X = function (x) { return L + (x - x0) / (x1 - x0) * (W - L - R); };
    var Y = function (y) { return T + (1 - Math.min(Math.max(isFinite(y) ? y : y1, 0), y1) / y1) * (H - T - B); };
    box.appendChild(svg("rect", { x: L, y: T, width: W - L - R, height: H - T - B, "class": "frame" }));
    for (var i = 0; i <= 4; i++) {
      var yv = y1 * i / 4;
      box.appendChild(svg("line", { x1: L, x2: W - R, y1: Y(yv), y2: Y(yv), "class": "grid" }));
      var t = svg("text", { x: L - 6, y: Y(yv) + 4, "text-anchor": "end" });
      t.textContent = fmt(yv);
      box.appendChild(t);
    }
    [x0, x1].forEach(function (xv) {
      var t = svg("text", { x: X(xv), y: H - B + 16, "text-anchor": "middle" });
      t.textContent = fmt(xv);
      box.appendChild(t);
    });
    var xl = svg("text", { x: (L + W - R) / 2, y: H - 6, "text-anchor": "middle" });
    xl.textContent = "frame";
    box.appendChild(xl);
    var yl = svg("text", { x: 14, y: (T + H - B) / 2, transform: "rotate(-90 14 " + (T + H - B) / 2 + ")", "text-anchor": "middle" });
    yl.textContent = yLabel;
    box.appendChild(yl);
    series.forEach(function (s) {
      var pts = s.values.map(function (v, k) { return X(xs[k]).toFixed(1) + "," + Y(v).toFixed(1); });
      var line = svg("polyline", { points: pts.join(" "), stroke: s.color, "class": "series " + s.style, "data-name": s.name });
      box.appendChild(line);
    });
    var cursor = svg("line", { x1: -10, x2: -10, y1: T, y2: H - B, "class": "cursor" });
    box.appendChild(cursor);
    cursors.push(function (frame) { cursor.setAttribute("x1", X(frame)); cursor.setAttribute("x2", X(frame)); });
    fig.appendChild(box);
    var cap = el("figcaption", null, title + " ");
    series.forEach(function (s) {
      var key = el("span", "key " + s.style);
      key.appendChild(el("i", s.side));
      key.appendChild(document.createTextNode(s.name));
      cap.appendChild(key);
    });
    fig.appendChild(cap);
    parent.appendChild(fig);
  }

  var mesh = data.kind === "mesh";
  var plots = section(mesh ? "Distribution" : "Per frame", "plots");
  var shearSeries = [];
  ["before", "after"].forEach(function (side) {
    [["mean", "solid"], ["p95", "dashed"], ["max", "dotted"]].forEach(function (st) {
      shearSeries.push({ name: st[0] + " " + side, side: side, style: st[1],
        color: side === "before" ? BEFORE : AFTER, values: column("shear_" + st[0] + "_" + side) });
    });
  });
  if (!mesh) linePlot(plots, "Shear (eq. 8) per frame, input (before) and output (after).", shearSeries, "shear");
  if (!mesh) linePlot(plots, "Distance between each output frame and its input frame (Metro-style, both ways).", [
    { name: "output to input, max", side: "after", style: "solid", color: AFTER, values: column("dist_out_to_in_max") },
    { name: "output to input, rms", side: "after", style: "dashed", color: AFTER, values: column("dist_out_to_in_rms") },
    { name: "input to output, max", side: "before", style: "solid", color: BEFORE, values: column("dist_in_to_out_max") },
    { name: "input to output, rms", side: "before", style: "dashed", color: BEFORE, values: column("dist_in_to_out_rms") }
  ], "distance");

  // --- Histogram of every triangle's shear over the frames.
  (function () {
    var h = data.histogram;
    if (!h) return;
    var W = 640, H = 240, L = 64, R = 12, T = 16, B = 40, n = h.before.length;
    var total = function (a) { return a.reduce(function (s, v) { return s + v; }, 0) || 1; };
    var tb = total(h.before), ta = total(h.after), ymax = 0;
    for (var i = 0; i < n; i++) ymax = Math.max(ymax, h.before[i] / tb, h.after[i] / ta);
    if (!(ymax > 0)) ymax = 1;
    var fig = el("figure", "plot");
    var box = svg("svg", { viewBox: "0 0 " + W + " " + H, role: "img", "class": "chart histogram" });
    var bw = (W - L - R) / n;
    box.appendChild(svg("rect", { x: L, y: T, width: W - L - R, height: H - T - B, "class": "frame" }));
    for (i = 0; i < n; i++) {
      [[h.before[i] / tb, BEFORE, 0], [h.after[i] / ta, AFTER, 0.5]].forEach(function (b) {
        var hh = b[0] / ymax * (H - T - B);
        box.appendChild(svg("rect", { x: L + i * bw + b[2] * bw, y: H - B - hh, width: bw / 2, height: hh, fill: b[1] }));
      });
    }
    [0, n >> 1, n - 1].forEach(function (k) {
      var t = svg("text", { x: L + k * bw, y: H - B + 16, "text-anchor": "middle" });
      t.textContent = fmt(h.edges[k]);
      box.appendChild(t);
    });
    var t = svg("text", { x: W - R, y: H - B + 16, "text-anchor": "end" });
    t.textContent = "and above";
    box.appendChild(t);
    var xl = svg("text", { x: (L + W - R) / 2, y: H - 6, "text-anchor": "middle" });
    xl.textContent = (data.player && data.player.colour === "radius ratio" ? "radius ratio" : "shear (eq. 8)") +
      " of a triangle; share of all triangles" + (data.kind === "mesh" ? "" : " of all frames");
    box.appendChild(xl);
    fig.appendChild(box);
    var cap = el("figcaption", null, "Histogram of every triangle's " +
      (data.player && data.player.colour === "radius ratio" ? "radius ratio" : "shear") + ". ");
    [["before", "input"], ["after", "output"]].forEach(function (s) {
      var key = el("span", "key solid");
      key.appendChild(el("i", s[0]));
      key.appendChild(document.createTextNode(s[1]));
      cap.appendChild(key);
    });
    fig.appendChild(cap);
    plots.appendChild(fig);
  })();

  // --- The summary table, sortable by any column.
  (function () {
    var s = section(data.kind === "mesh" ? "Measures (measures.csv)" : "Summary (summary.csv)", "summary");
    var wrap = el("div", "table-wrap");
    var table = el("table", "summary");
    var thead = el("thead"), tr = el("tr");
    var order = { col: 0, dir: 1 };
    columns.forEach(function (c, k) {
      var th = el("th", null, c);
      th.setAttribute("data-col", String(k));
      th.addEventListener("click", function () {
        order.dir = order.col === k ? -order.dir : 1;
        order.col = k;
        fill();
      });
      tr.appendChild(th);
    });
    thead.appendChild(tr);
    table.appendChild(thead);
    var tbody = el("tbody");
    table.appendChild(tbody);
    function key(v) { var x = num(v); return isNaN(x) ? v : x; }
    function fill() {
      var sorted = rows.slice().sort(function (a, b) {
        var x = key(a[order.col]), y = key(b[order.col]);
        if (typeof x !== typeof y) { x = String(x); y = String(y); }
        return (x < y ? -1 : x > y ? 1 : 0) * order.dir;
      });
      tbody.textContent = "";
      sorted.forEach(function (r) {
        var row = el("tr", r[columns.indexOf("status")] === "failed" ? "failed" : null);
        r.forEach(function (v) { row.appendChild(el("td", null, v)); });
        tbody.appendChild(row);
      });
    }
    fill();
    wrap.appendChild(table);
    s.appendChild(wrap);
  })();

  // --- Failures, warnings, config, versions.
  function list(title, id, items, empty) {
    var s = section(title, id);
    if (!items.length) { s.appendChild(el("p", "note", empty)); return; }
    var ul = el("ul");
    items.forEach(function (t) { ul.appendChild(el("li", null, t)); });
    s.appendChild(ul);
  }
  list("Failed frames", "failures", (data.failures || []).map(function (f) {
    return "frame " + f.frame + " (" + f.file + "): " + f.reason;
  }), "None.");
  list("Warnings", "warnings", data.warnings || [], "None.");
  var cs = section("Configuration (resolved)", "config");
  cs.appendChild(el("pre", null, JSON.stringify(data.config, null, 2)));
  var vs = section("Versions", "versions");
  var vt = el("table", "versions");
  Object.keys(data.versions || {}).forEach(function (k) {
    var r = el("tr");
    r.appendChild(el("th", null, k));
    r.appendChild(el("td", null, data.versions[k]));
    vt.appendChild(r);
  });
  vs.appendChild(vt);
  window.seqmassageReport = { data: data, player: player };
})();
