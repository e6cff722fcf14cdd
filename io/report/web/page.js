// ComicPage: draws a comic-sfm report page from the JSON inside it (io/report/html_page.h).
// Each section of data.sections has a "type" naming its renderer: the ones here draw text,
// tables and pictures; charts.js adds the charts and scene.js the 3-D view. A renderer that
// throws leaves its message in its section and in #comic-page-errors; when every section is
// drawn, <html data-comic-page> says "drawn" (or "error"), which the headless-browser tests read.
(function () {
  'use strict';

  var errors = [];
  var renderers = {};

  function recordError(message) {
    errors.push(String(message));
    var box = document.getElementById('comic-page-errors');
    if (box) {
      box.hidden = false;
      box.textContent = 'Script errors:\n' + errors.join('\n');
    }
    if (document.documentElement.getAttribute('data-comic-page') !== 'loading') {
      document.documentElement.setAttribute('data-comic-page', 'error');
    }
  }

  window.addEventListener('error', function (event) {
    recordError((event.message || 'error') + ' (' + (event.filename || 'page') + ':' +
                (event.lineno || 0) + ')');
  });

  // el('p', {class: 'note'}, ['text', child]): an element with attributes and children.
  function el(tag, attributes, children) {
    var node = document.createElement(tag);
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

  function note(text) {
    return text ? el('p', {class: 'note'}, [text]) : null;
  }

  // A legend: [{color, label}] as swatches; `style(entry, swatch)` may restyle a swatch.
  function legend(entries, style) {
    var box = el('div', {class: 'legend'});
    entries.forEach(function (entry) {
      var swatch = el('span', {class: 'swatch'});
      swatch.style.background = entry.color;
      if (style) style(entry, swatch);
      box.appendChild(el('span', {}, [swatch, entry.label]));
    });
    return box;
  }

  // A number with `digits` decimals, or '–' for none.
  function format(value, digits) {
    if (value === null || value === undefined || !isFinite(value)) return '–';
    return Number(value).toFixed(digits === undefined ? 3 : digits);
  }

  renderers.facts = function (section, body) {
    var list = el('dl', {class: 'facts'});
    section.facts.forEach(function (fact) {
      list.appendChild(el('dt', {}, [fact.label]));
      var value = el('dd', {}, [fact.value]);
      if (fact.tone !== 'neutral') value.className = 'tone-' + fact.tone;
      list.appendChild(value);
    });
    body.appendChild(list);
  };

  renderers.notice = function (section, body) {
    body.appendChild(el('p', {class: 'notice tone-' + section.tone}, [section.text]));
  };

  renderers.text = function (section, body) {
    section.paragraphs.forEach(function (text) { body.appendChild(el('p', {}, [text])); });
  };

  renderers.table = function (section, body) {
    var head = el('tr', {}, section.columns.map(function (c) { return el('th', {}, [c]); }));
    var rows = section.rows.map(function (row, r) {
      return el('tr', {}, row.map(function (cell, c) {
        var content = cell === '' ? '–' : cell;
        if (c === 0 && section.links && section.links[r]) {
          content = el('a', {href: section.links[r]}, [content]);
        }
        return el('td', section.numeric[c] ? {class: 'num'} : {}, [content]);
      }));
    });
    var table = el('table', {class: 'data'}, [el('thead', {}, [head]), el('tbody', {}, rows)]);
    // A long table (one row per frame) scrolls in a box of its own.
    body.appendChild(el('div', {class: section.scroll ? 'table-scroll tall' : 'table-scroll'},
                        [table]));
    body.appendChild(note(section.note) || document.createTextNode(''));
  };

  renderers.images = function (section, body) {
    var box = el('div', {class: section.thumbnails ? 'strip' : 'images'});
    section.images.forEach(function (image) {
      var figure = el('figure', image.tone ? {class: 'tone-' + image.tone} : {}, [
        el('img', {src: image.src, alt: image.caption, title: image.caption, loading: 'lazy'}),
        el('figcaption', {}, [image.caption])
      ]);
      box.appendChild(figure);
    });
    if (section.legend.length) body.appendChild(legend(section.legend));
    body.appendChild(box);
    body.appendChild(note(section.note) || document.createTextNode(''));
  };

  renderers.keyvalues = function (section, body) {
    var rows = section.rows.map(function (row) {
      var value = row[1];
      var text = (value !== null && typeof value === 'object') ? JSON.stringify(value)
                                                                : String(value);
      return el('tr', {}, [el('th', {}, [row[0]]), el('td', {}, [text])]);
    });
    body.appendChild(el('div', {class: 'table-scroll'},
                        [el('table', {class: 'data'}, [el('tbody', {}, rows)])]));
  };

  renderers.json = function (section, body) {
    var details = el('details', {}, [el('summary', {}, ['show']),
                                     el('pre', {class: 'json'},
                                        [JSON.stringify(section.document, null, 2)])]);
    body.appendChild(details);
  };

  function drawSection(section, index, main, nav) {
    var id = 'section-' + index;
    var body = el('div', {class: 'section-body'});
    var box = el('section', {id: id, class: 'section section-' + section.type},
                 [section.title ? el('h2', {}, [section.title]) : null, body]);
    main.appendChild(box);
    if (section.title) nav.appendChild(el('a', {href: '#' + id}, [section.title]));
    var renderer = renderers[section.type];
    try {
      if (!renderer) throw new Error('no renderer for sections of type "' + section.type + '"');
      renderer(section, body, ComicPage.data);
    } catch (error) {
      recordError('section "' + (section.title || section.type) + '": ' +
                  (error && error.stack ? error.stack : error));
      body.appendChild(el('p', {class: 'notice tone-bad'},
                          ['This section could not be drawn: ' + error]));
    }
  }

  function render() {
    var root = document.documentElement;
    try {
      var data = JSON.parse(document.getElementById('comic-page-data').textContent);
      ComicPage.data = data;
      document.getElementById('page-subtitle').textContent = data.subtitle || '';
      var main = document.getElementById('page-sections');
      var nav = document.getElementById('page-nav');
      data.sections.forEach(function (section, index) { drawSection(section, index, main, nav); });
      document.getElementById('page-footer').textContent =
          'Written by ' + data.generator + '. Everything on this page is in this one file; ' +
          'it opens offline.';
    } catch (error) {
      recordError('page: ' + (error && error.stack ? error.stack : error));
    }
    root.setAttribute('data-comic-page', errors.length ? 'error' : 'drawn');
  }

  window.ComicPage = {
    renderers: renderers,
    el: el,
    note: note,
    legend: legend,
    format: format,
    recordError: recordError,
    render: render,
    data: null
  };
})();
