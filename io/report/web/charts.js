// Charts of a comic-sfm report page (io/report/page_sections.h, page_charts.h), drawn as SVG:
// grouped bars, values along the frames, a top view of camera paths with equal scale on both
// axes, and the registration timeline (a canvas: one cell per frame, up to any length).
(function () {
  'use strict';

  var page = window.ComicPage;
  var el = page.el;
  var SVG = 'http://www.w3.org/2000/svg';
  // Okabe & Ito's colour-blind-safe palette, as io/report/bar_chart.cc draws the PNGs.
  var PALETTE = ['#0072B2', '#E69F00', '#009E73', '#CC79A7', '#F0E442', '#D55E00', '#56B4E9',
                 '#000000'];

  function svg(tag, attributes, children) {
    var node = document.createElementNS(SVG, tag);
    var key;
    for (key in attributes || {}) {
      if (Object.prototype.hasOwnProperty.call(attributes, key)) {
        node.setAttribute(key, attributes[key]);
      }
    }
    (children || []).forEach(function (child) {
      if (child === null || child === undefined) return;
      node.appendChild(typeof child === 'string' ? document.createTextNode(child) : child);
    });
    return node;
  }

  function text(x, y, content, attributes) {
    var a = attributes || {};
    a.x = x;
    a.y = y;
    return svg('text', a, [content]);
  }

  // Round tick values covering [low, high]: steps of 1, 2 or 5 times a power of ten.
  function ticks(low, high, count) {
    if (!(high > low)) high = low + 1;
    var raw = (high - low) / Math.max(1, count);
    var power = Math.pow(10, Math.floor(Math.log(raw) / Math.LN10));
    var step = power;
    [1, 2, 5, 10].some(function (m) { step = m * power; return step >= raw; });
    var values = [];
    var first = Math.ceil(low / step - 1e-9) * step;
    for (var v = first; v <= high + step * 1e-9; v += step) values.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    return {values: values, step: step};
  }

  function tickLabel(value, step) {
    var digits = Math.max(0, -Math.floor(Math.log(step) / Math.LN10 + 1e-9));
    return value.toFixed(Math.min(digits, 6));
  }

  function finite(v) { return v !== null && v !== undefined && isFinite(v); }

  function chartBox(width, height) {
    return svg('svg', {class: 'chart', viewBox: '0 0 ' + width + ' ' + height, width: width,
                       height: height, role: 'img'});
  }

  // A y axis with ticks, grid and its rotated label.
  function yAxis(chart, scale, box, label) {
    scale.ticks.values.forEach(function (v) {
      var y = scale.y(v);
      chart.appendChild(svg('line', {class: 'grid', x1: box.left, x2: box.right, y1: y, y2: y}));
      chart.appendChild(text(box.left - 6, y + 4, tickLabel(v, scale.ticks.step),
                             {'text-anchor': 'end'}));
    });
    chart.appendChild(svg('line', {class: 'axis', x1: box.left, x2: box.left, y1: box.top,
                                   y2: box.bottom}));
    var middle = (box.top + box.bottom) / 2;
    chart.appendChild(text(14, middle, label || '', {
      'text-anchor': 'middle', transform: 'rotate(-90 14 ' + middle + ')', 'font-size': 12}));
  }

  function linearScale(low, high, pixelLow, pixelHigh, count) {
    var t = ticks(low, high, count);
    var lo = Math.min(low, t.values[0]);
    var hi = Math.max(high, t.values[t.values.length - 1]);
    if (!(hi > lo)) hi = lo + 1;
    return {
      ticks: t,
      low: lo,
      high: hi,
      y: function (v) { return pixelLow + (pixelHigh - pixelLow) * (v - lo) / (hi - lo); }
    };
  }

  // One bar chart: a cluster of bars per group, one colour per series, value labels on top.
  function barChart(chart, width, height) {
    var box = {left: 70, right: width - 14, top: 18, bottom: height - 30};
    var max = 0;
    chart.series.forEach(function (s) {
      s.values.forEach(function (v) { if (finite(v)) max = Math.max(max, v); });
    });
    var scale = linearScale(0, max > 0 ? max : 1, box.bottom, box.top, 5);
    var figure = chartBox(width, height);
    yAxis(figure, scale, box, chart.y_label);
    var groupWidth = (box.right - box.left) / Math.max(1, chart.groups.length);
    var barWidth = groupWidth * 0.8 / Math.max(1, chart.series.length);
    chart.groups.forEach(function (group, g) {
      var left = box.left + g * groupWidth + groupWidth * 0.1;
      chart.series.forEach(function (s, k) {
        var v = s.values[g];
        if (!finite(v)) return;
        var x = left + k * barWidth;
        var y = scale.y(Math.max(0, v));
        figure.appendChild(svg('rect', {x: x, y: y, width: Math.max(1, barWidth - 2),
                                        height: Math.max(0, box.bottom - y),
                                        fill: PALETTE[k % PALETTE.length]},
                               [svg('title', {}, [s.name + ' · ' + group + ': ' + v])]));
        var label = Math.round(v) === v ? String(v) : (Math.abs(v) >= 100 ? v.toFixed(0) :
                                                        v.toPrecision(3));
        figure.appendChild(text(x + (barWidth - 2) / 2, y - 3, label,
                                {'text-anchor': 'middle', 'font-size': 10}));
      });
      figure.appendChild(text(box.left + (g + 0.5) * groupWidth, box.bottom + 16, group,
                              {'text-anchor': 'middle', 'font-size': 12}));
    });
    figure.appendChild(svg('line', {class: 'axis', x1: box.left, x2: box.right, y1: box.bottom,
                                    y2: box.bottom}));
    return figure;
  }

  // A bar chart (io/report/page_sections.h BarChartSection), or several side by side sharing
  // their series' colours (BarChartsSection).
  page.renderers.bars = function (section, body) {
    var charts = section.charts || [section];
    var series = charts[0].series;
    body.appendChild(page.legend(series.map(function (s, k) {
      return {color: PALETTE[k % PALETTE.length], label: s.name};
    })));
    var grid = el('div', {class: charts.length > 1 ? 'chart-grid' : ''});
    charts.forEach(function (chart) {
      var cell = el('div', {}, [charts.length > 1 ? el('h3', {}, [chart.title]) : null]);
      cell.appendChild(charts.length > 1 ? barChart(chart, 380, 250) : barChart(chart, 900, 320));
      grid.appendChild(cell);
    });
    body.appendChild(grid);
    if (section.note) body.appendChild(page.note(section.note));
  };

  // Polyline path data through the finite points, broken at the others.
  function pathData(points) {
    var d = '';
    var pen = false;
    points.forEach(function (p) {
      if (!p) { pen = false; return; }
      d += (pen ? 'L' : 'M') + p[0].toFixed(1) + ' ' + p[1].toFixed(1);
      pen = true;
    });
    return d;
  }

  page.renderers.lines = function (section, body) {
    var width = 900, height = 300;
    var box = {left: 70, right: width - 14, top: 14, bottom: height - 58};
    var xs = [], ys = [0];
    section.series.forEach(function (s) {
      s.x.forEach(function (x, i) { if (finite(x) && finite(s.y[i])) { xs.push(x); ys.push(s.y[i]); } });
    });
    section.marks.forEach(function (m) { m.x.forEach(function (x) { if (finite(x)) xs.push(x); }); });
    if (!xs.length) xs = [0, 1];
    var xLow = Math.min.apply(null, xs), xHigh = Math.max.apply(null, xs);
    var yScale = linearScale(0, Math.max.apply(null, ys), box.bottom, box.top, 5);
    var xTicks = ticks(xLow, xHigh, 10);
    var xOf = function (x) {
      return box.left + (box.right - box.left) * (x - xLow) / (xHigh > xLow ? xHigh - xLow : 1);
    };
    var chart = chartBox(width, height);
    yAxis(chart, yScale, box, section.y_label);
    xTicks.values.forEach(function (x) {
      chart.appendChild(svg('line', {class: 'axis', x1: xOf(x), x2: xOf(x), y1: box.bottom,
                                     y2: box.bottom + 4}));
      chart.appendChild(text(xOf(x), box.bottom + 16, tickLabel(x, xTicks.step),
                             {'text-anchor': 'middle'}));
    });
    chart.appendChild(svg('line', {class: 'axis', x1: box.left, x2: box.right, y1: box.bottom,
                                   y2: box.bottom}));
    chart.appendChild(text((box.left + box.right) / 2, height - 6, section.x_label,
                           {'text-anchor': 'middle', 'font-size': 12}));
    section.series.forEach(function (s) {
      var points = s.x.map(function (x, i) {
        return finite(x) && finite(s.y[i]) ? [xOf(x), yScale.y(s.y[i])] : null;
      });
      chart.appendChild(svg('path', {d: pathData(points), fill: 'none', stroke: s.color,
                                     'stroke-width': 1.6}));
      if (points.filter(Boolean).length <= 400) {
        points.forEach(function (p) {
          if (p) chart.appendChild(svg('circle', {cx: p[0], cy: p[1], r: 2, fill: s.color}));
        });
      }
    });
    // Marks: short ticks in a band under the axis labels.
    section.marks.forEach(function (m, k) {
      var y = box.bottom + 22 + 6 * k;
      m.x.forEach(function (x) {
        if (!finite(x)) return;
        chart.appendChild(svg('line', {x1: xOf(x), x2: xOf(x), y1: y, y2: y + 5, stroke: m.color,
                                       'stroke-width': 1.5}));
      });
    });
    var entries = section.series.map(function (s) { return {color: s.color, label: s.name}; })
        .concat(section.marks.map(function (m) {
          return {color: m.color, label: m.label + ' (ticks under the axis)'};
        }));
    body.appendChild(page.legend(entries));
    body.appendChild(chart);
    var readout = el('div', {class: 'readout'}, ['point at the chart to read the values']);
    body.appendChild(readout);
    chart.addEventListener('mousemove', function (event) {
      var rect = chart.getBoundingClientRect();
      var px = (event.clientX - rect.left) * width / rect.width;
      var x = xLow + (px - box.left) / (box.right - box.left) * (xHigh - xLow);
      var parts = [section.x_label + ' ' + Math.round(x)];
      section.series.forEach(function (s) {
        var best = -1;
        s.x.forEach(function (sx, i) {
          if (best < 0 || Math.abs(sx - x) < Math.abs(s.x[best] - x)) best = i;
        });
        if (best >= 0 && Math.abs(s.x[best] - x) <= 0.5) {
          parts.push(s.name + ': ' + page.format(s.y[best], 4));
        }
      });
      readout.textContent = parts.join('   ');
    });
    if (section.note) body.appendChild(page.note(section.note));
  };

  page.renderers.topview = function (section, body) {
    var size = 640, margin = {left: 70, right: 16, top: 14, bottom: 52};
    var all = [];
    section.series.forEach(function (s) { s.points.forEach(function (p) { if (p) all.push(p); }); });
    if (!all.length) {
      body.appendChild(el('p', {class: 'note'}, ['no camera positions to draw']));
      return;
    }
    var lowX = Math.min.apply(null, all.map(function (p) { return p[0]; }));
    var highX = Math.max.apply(null, all.map(function (p) { return p[0]; }));
    var lowY = Math.min.apply(null, all.map(function (p) { return p[1]; }));
    var highY = Math.max.apply(null, all.map(function (p) { return p[1]; }));
    var extent = Math.max(highX - lowX, highY - lowY, 1e-9) * 1.08;
    var midX = (lowX + highX) / 2, midY = (lowY + highY) / 2;
    var inner = size - margin.left - margin.right;
    var width = size, height = inner + margin.top + margin.bottom;
    var pxPerUnit = inner / extent;
    var X = function (x) { return margin.left + inner / 2 + (x - midX) * pxPerUnit; };
    var Y = function (y) { return margin.top + inner / 2 - (y - midY) * pxPerUnit; };
    var chart = chartBox(width, height);
    // One tick step on both axes (equal scale): a grid in metres (or the model's units).
    var t = ticks(midX - extent / 2, midX + extent / 2, 8);
    var step = t.step;
    var yValues = [];
    for (var v = Math.ceil((midY - extent / 2) / step) * step; v <= midY + extent / 2; v += step) {
      yValues.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    }
    var unit = section.unit ? ' (' + section.unit + ')' : '';
    t.values.forEach(function (x) {
      chart.appendChild(svg('line', {class: 'grid', x1: X(x), x2: X(x), y1: margin.top,
                                     y2: margin.top + inner}));
      chart.appendChild(text(X(x), margin.top + inner + 14, tickLabel(x, step),
                             {'text-anchor': 'middle'}));
    });
    yValues.forEach(function (y) {
      chart.appendChild(svg('line', {class: 'grid', x1: margin.left, x2: margin.left + inner,
                                     y1: Y(y), y2: Y(y)}));
      chart.appendChild(text(margin.left - 6, Y(y) + 4, tickLabel(y, step), {'text-anchor': 'end'}));
    });
    chart.appendChild(svg('rect', {x: margin.left, y: margin.top, width: inner, height: inner,
                                   fill: 'none', class: 'axis'}));
    chart.appendChild(text(margin.left + inner / 2, margin.top + inner + 32,
                           section.right_label + unit, {'text-anchor': 'middle', 'font-size': 12}));
    var midPx = margin.top + inner / 2;
    chart.appendChild(text(14, midPx, section.up_label + unit, {
      'text-anchor': 'middle', transform: 'rotate(-90 14 ' + midPx + ')', 'font-size': 12}));
    // Scale bar: one grid step.
    var barY = height - 8;
    chart.appendChild(svg('line', {x1: margin.left, x2: margin.left + step * pxPerUnit, y1: barY,
                                   y2: barY, stroke: '#1d2329', 'stroke-width': 3}));
    chart.appendChild(text(margin.left + step * pxPerUnit + 6, barY + 4,
                           tickLabel(step, step) + ' ' + (section.unit || 'units') +
                           ' (one grid step; equal scale on both axes)'));
    if (section.links) {
      var a = section.series[section.links[0]].points, b = section.series[section.links[1]].points;
      a.forEach(function (p, i) {
        if (p && b[i]) {
          chart.appendChild(svg('line', {x1: X(p[0]), y1: Y(p[1]), x2: X(b[i][0]), y2: Y(b[i][1]),
                                         stroke: '#9aa3ab', 'stroke-width': 1}));
        }
      });
    }
    section.series.forEach(function (s) {
      var points = s.points.map(function (p) { return p ? [X(p[0]), Y(p[1])] : null; });
      if (s.line) {
        chart.appendChild(svg('path', {d: pathData(points), fill: 'none', stroke: s.color,
                                       'stroke-width': s.width, 'stroke-linejoin': 'round',
                                       'stroke-opacity': 0.85}));
        var first = points.filter(Boolean)[0];
        if (first) {
          chart.appendChild(svg('circle', {cx: first[0], cy: first[1], r: 6, fill: 'none',
                                           stroke: s.color, 'stroke-width': 1.5},
                                [svg('title', {}, [s.name + ': first frame'])]));
        }
      }
      if (s.marker === 'none') return;
      points.forEach(function (p, i) {
        if (!p) return;
        var label = svg('title', {}, [s.name + ', frame ' + i]);
        if (s.marker === 'cross') {
          var r = s.width;
          chart.appendChild(svg('path', {d: 'M' + (p[0] - r) + ' ' + (p[1] - r) + 'L' + (p[0] + r) +
                                            ' ' + (p[1] + r) + 'M' + (p[0] - r) + ' ' + (p[1] + r) +
                                            'L' + (p[0] + r) + ' ' + (p[1] - r),
                                         stroke: s.color, 'stroke-width': 1.8}, [label]));
        } else {
          chart.appendChild(svg('circle', {cx: p[0], cy: p[1], r: s.line ? 1.6 : s.width,
                                           fill: s.color}, [label]));
        }
      });
    });
    body.appendChild(page.legend(section.series.map(function (s) {
      return {color: s.color, label: s.name};
    }).concat(section.links ? [{color: '#9aa3ab', label: 'error of each camera (grey segment)'}]
                            : [])));
    body.appendChild(chart);
    if (section.note) body.appendChild(page.note(section.note));
  };

  // The registration timeline: cells wrapped into rows, coloured by state and model.
  page.renderers.timeline = function (section, body) {
    var n = section.frame_states.length;
    var width = 1100;
    var cell = Math.max(3, Math.min(28, Math.floor((width - 60) / Math.max(1, n))));
    var perRow = Math.max(1, Math.floor((width - 60) / cell));
    var rows = Math.ceil(n / perRow);
    var rowHeight = 18;
    var height = Math.max(1, rows) * rowHeight + 4;
    var canvas = el('canvas', {width: width, height: height});
    canvas.style.width = '100%';
    canvas.style.maxWidth = width + 'px';
    var g = canvas.getContext('2d');
    g.font = '10px sans-serif';
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, width, height);
    function colorOf(i) {
      var state = section.states[section.frame_states[i]];
      var group = section.frame_groups[i];
      return state.color || (group >= 0 ? section.groups[group].color : '#999999');
    }
    for (var i = 0; i < n; ++i) {
      var state = section.states[section.frame_states[i]];
      var x = 56 + (i % perRow) * cell, y = 2 + Math.floor(i / perRow) * rowHeight;
      var w = Math.max(1, cell - (cell > 4 ? 1 : 0)), h = rowHeight - 4;
      var color = colorOf(i);
      if (state.style === 'outline') {
        g.fillStyle = '#ffffff';
        g.fillRect(x, y, w, h);
        g.strokeStyle = color;
        g.lineWidth = 1.5;
        g.strokeRect(x + 0.75, y + 0.75, Math.max(0.5, w - 1.5), h - 1.5);
      } else {
        g.globalAlpha = state.style === 'light' ? 0.4 : 1;
        g.fillStyle = color;
        g.fillRect(x, y, w, h);
        g.globalAlpha = 1;
        if (state.style === 'marked') {
          g.fillStyle = '#1d2329';
          g.fillRect(x, y, w, 4);
        }
      }
      if (i % perRow === 0) {
        g.fillStyle = '#5f6b76';
        g.fillText(String(i), 2, y + 11);
      }
    }
    var used = {};
    var usedGroups = {};
    section.frame_states.forEach(function (s, f) {
      used[s] = true;
      if (section.frame_groups[f] >= 0) usedGroups[section.frame_groups[f]] = true;
    });
    var firstGroupColor = section.groups.length ? section.groups[0].color : '#999999';
    var entries = [];
    section.states.forEach(function (s, k) {
      if (used[k]) entries.push({color: s.color || firstGroupColor, label: s.label, style: s.style});
    });
    section.groups.forEach(function (grp, k) {
      if (usedGroups[k]) entries.push({color: grp.color, label: grp.label, style: 'solid'});
    });
    body.appendChild(page.legend(entries, function (entry, swatch) {
      if (entry.style === 'outline') {
        swatch.style.background = '#ffffff';
        swatch.style.border = '2px solid ' + entry.color;
      } else if (entry.style === 'light') {
        swatch.style.opacity = '0.45';
      } else if (entry.style === 'marked') {
        swatch.style.borderTop = '4px solid #1d2329';
      }
    }));
    body.appendChild(el('div', {class: 'timeline'}, [canvas]));
    var readout = el('div', {class: 'readout'}, ['point at a cell to see its frame']);
    body.appendChild(readout);
    canvas.addEventListener('mousemove', function (event) {
      var rect = canvas.getBoundingClientRect();
      var px = (event.clientX - rect.left) * width / rect.width;
      var py = (event.clientY - rect.top) * height / rect.height;
      var f = Math.floor((py - 2) / rowHeight) * perRow + Math.floor((px - 56) / cell);
      if (px < 56 || f < 0 || f >= n) return;
      var words = 'frame ' + f + (section.frame_names.length ? ' (' + section.frame_names[f] + ')' : '') +
                  ': ' + section.states[section.frame_states[f]].label;
      if (section.frame_groups[f] >= 0) words += ', ' + section.groups[section.frame_groups[f]].label;
      section.notes.forEach(function (nt) {
        if (f >= nt.first && f <= nt.last) words += ' — ' + nt.text;
      });
      readout.textContent = words;
    });
    if (section.notes.length) {
      var noteRows = section.notes.map(function (nt) {
        return el('tr', {}, [el('td', {class: 'num'}, [nt.first === nt.last ? String(nt.first) :
                                                       nt.first + '–' + nt.last]),
                             el('td', {}, [nt.text])]);
      });
      body.appendChild(el('div', {class: 'table-scroll'}, [el('table', {class: 'data'}, [
        el('thead', {}, [el('tr', {}, [el('th', {}, ['frames']), el('th', {}, ['why'])])]),
        el('tbody', {}, noteRows)])]));
    }
    if (section.note) body.appendChild(page.note(section.note));
  };

  // A histogram (io/report/page_distributions.h): one bar per bin, and the values beyond the
  // last edge as one more bar in grey.
  page.renderers.histogram = function (section, body) {
    var width = 900, height = 300;
    var box = {left: 70, right: width - 14, top: 18, bottom: height - 46};
    var bins = section.counts.length;
    var slots = bins + (section.overflow > 0 ? 1 : 0);
    var max = Math.max.apply(null, section.counts.concat([section.overflow, 1]));
    var scale = linearScale(0, max, box.bottom, box.top, 5);
    var slot = (box.right - box.left) / Math.max(1, slots);
    var chart = chartBox(width, height);
    yAxis(chart, scale, box, section.y_label);
    var bar = function (k, count, color, words) {
      var y = scale.y(count);
      chart.appendChild(svg('rect', {x: box.left + k * slot + 1, y: y,
                                     width: Math.max(1, slot - 2), height: Math.max(0, box.bottom - y),
                                     fill: color}, [svg('title', {}, [words + ': ' + count])]));
    };
    var last = section.edges[bins];
    var step = section.edges[1] - section.edges[0];
    section.counts.forEach(function (count, k) {
      bar(k, count, section.color, tickLabel(section.edges[k], step / 10) + '–' +
          tickLabel(section.edges[k + 1], step / 10));
    });
    if (section.overflow > 0) bar(bins, section.overflow, '#9aa3ab', 'beyond ' + last);
    var every = Math.max(1, Math.ceil(bins / 10));
    for (var k = 0; k <= bins; k += every) {
      var x = box.left + k * slot;
      chart.appendChild(svg('line', {class: 'axis', x1: x, x2: x, y1: box.bottom, y2: box.bottom + 4}));
      chart.appendChild(text(x, box.bottom + 16, tickLabel(section.edges[k], step),
                             {'text-anchor': 'middle'}));
    }
    if (section.overflow > 0) {
      chart.appendChild(text(box.left + (bins + 0.5) * slot, box.bottom + 30, '> ' + tickLabel(last, step),
                             {'text-anchor': 'middle'}));
    }
    chart.appendChild(svg('line', {class: 'axis', x1: box.left, x2: box.right, y1: box.bottom,
                                   y2: box.bottom}));
    chart.appendChild(text((box.left + box.right) / 2, height - 8, section.x_label,
                           {'text-anchor': 'middle', 'font-size': 12}));
    body.appendChild(chart);
    if (section.note) body.appendChild(page.note(section.note));
  };

  // White (nothing shared) to dark blue (the most), on a square-root scale so that weak links
  // still show beside strong ones.
  function heatColor(value, max) {
    if (!(value > 0)) return [255, 255, 255];
    var t = Math.sqrt(Math.min(1, value / max));
    var low = [222, 235, 247], high = [8, 48, 107];
    return low.map(function (c, i) { return Math.round(c + (high[i] - c) * t); });
  }

  // A square matrix between frames (io/report/page_distributions.h HeatMap) on a canvas, one
  // cell per frame or group of frames; pointing at a cell reads its frames and value.
  page.renderers.heatmap = function (section, body) {
    var n = section.cell_first_frames.length;
    var pixel = Math.max(1, Math.floor(600 / Math.max(1, n)));
    var margin = 44, side = n * pixel;
    var canvas = el('canvas', {width: side + margin, height: side + margin});
    var g = canvas.getContext('2d');
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, side + margin, side + margin);
    var max = 0;
    section.values.forEach(function (v) { max = Math.max(max, v); });
    var image = g.createImageData(side, side);
    for (var r = 0; r < n; ++r) {
      for (var c = 0; c < n; ++c) {
        var color = heatColor(section.values[r * n + c], max);
        for (var dy = 0; dy < pixel; ++dy) {
          for (var dx = 0; dx < pixel; ++dx) {
            var at = 4 * ((r * pixel + dy) * side + c * pixel + dx);
            image.data[at] = color[0];
            image.data[at + 1] = color[1];
            image.data[at + 2] = color[2];
            image.data[at + 3] = 255;
          }
        }
      }
    }
    g.putImageData(image, margin, margin);
    g.strokeStyle = '#1d2329';
    g.strokeRect(margin - 0.5, margin - 0.5, side + 1, side + 1);
    g.fillStyle = '#5f6b76';
    g.font = '10px sans-serif';
    var labelled = ticks(0, Math.max(1, section.num_frames - 1), 6);
    var cellOf = function (frame) {
      var k = 0;
      while (k + 1 < n && section.cell_first_frames[k + 1] <= frame) ++k;
      return k;
    };
    labelled.values.forEach(function (frame) {
      if (frame >= section.num_frames) return;
      var at = margin + (cellOf(frame) + 0.5) * pixel;
      g.textAlign = 'center';
      g.fillText(String(frame), at, margin - 6);
      g.textAlign = 'right';
      g.fillText(String(frame), margin - 4, at + 3);
    });
    var framesOf = function (k) {
      var first = section.cell_first_frames[k];
      var last = k + 1 < n ? section.cell_first_frames[k + 1] - 1 : section.num_frames - 1;
      return first === last ? 'frame ' + first : 'frames ' + first + '–' + last;
    };
    var readout = el('div', {class: 'readout'}, ['point at a cell to read it']);
    canvas.addEventListener('mousemove', function (event) {
      var rect = canvas.getBoundingClientRect();
      var x = (event.clientX - rect.left) * canvas.width / rect.width - margin;
      var y = (event.clientY - rect.top) * canvas.height / rect.height - margin;
      var row = Math.floor(y / pixel), column = Math.floor(x / pixel);
      if (row < 0 || column < 0 || row >= n || column >= n) return;
      readout.textContent = framesOf(row) + ' × ' + framesOf(column) + ': ' +
          section.values[row * n + column] + ' ' + section.value_label;
    });
    body.appendChild(page.legend([
      {color: 'rgb(' + heatColor(max, max).join(',') + ')', label: max + ' ' + section.value_label},
      {color: 'rgb(' + heatColor(1, Math.max(1, max * 16)).join(',') + ')', label: 'few'},
      {color: '#ffffff', label: 'none'}], function (entry, swatch) {
        swatch.style.border = '1px solid #d8dde2';
      }));
    body.appendChild(el('div', {class: 'heatmap'}, [canvas]));
    body.appendChild(readout);
    if (section.note) body.appendChild(page.note(section.note));
  };

  page.PALETTE = PALETTE;
})();
