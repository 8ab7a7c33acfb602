// Sorting and filtering for report.html's tables, inlined into the page (nothing fetched).
// table.sortable: a click on a header sorts by that column (numbers by their data-v value).
// table.filterable: div.filters[data-for=ID] gets a select per header with data-col, and a text box.
(function () {
  'use strict';

  function cellValue(row, index) {
    var cell = row.cells[index];
    if (!cell) return '';
    var v = cell.getAttribute('data-v');
    return v !== null ? parseFloat(v) : cell.textContent.trim().toLowerCase();
  }

  function compare(a, b) {
    var an = typeof a === 'number', bn = typeof b === 'number';
    if (an && bn) return a - b;
    if (an) return -1;  // numbers before dashes and words
    if (bn) return 1;
    return a < b ? -1 : a > b ? 1 : 0;
  }

  function sortBy(table, index, descending) {
    var body = table.tBodies[0];
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (x, y) {
      var c = compare(cellValue(x, index), cellValue(y, index));
      return descending ? -c : c;
    });
    rows.forEach(function (r) { body.appendChild(r); });
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th, i) {
      th.classList.remove('asc', 'desc');
      if (i === index) th.classList.add(descending ? 'desc' : 'asc');
    });
  }

  function makeSortable(table) {
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th, i) {
      th.title = 'sort by ' + th.textContent.trim();
      th.addEventListener('click', function () { sortBy(table, i, th.classList.contains('asc')); });
    });
  }

  function applyFilters(table, bar) {
    var selects = bar.querySelectorAll('select');
    var text = bar.querySelector('input').value.trim().toLowerCase();
    var shown = 0, rows = table.tBodies[0].rows;
    Array.prototype.forEach.call(rows, function (row) {
      var keep = Array.prototype.every.call(selects, function (s) {
        return s.value === '' || row.cells[+s.getAttribute('data-index')].textContent.trim() === s.value;
      });
      keep = keep && (text === '' || row.textContent.toLowerCase().indexOf(text) >= 0);
      row.style.display = keep ? '' : 'none';
      if (keep) shown++;
    });
    bar.querySelector('.count').textContent = shown + ' of ' + rows.length + ' rows';
  }

  function makeFilterable(table, bar) {
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th, i) {
      var col = th.getAttribute('data-col');
      if (!col) return;
      var values = {};
      Array.prototype.forEach.call(table.tBodies[0].rows, function (r) { values[r.cells[i].textContent.trim()] = true; });
      var label = document.createElement('label');
      label.textContent = col + ' ';
      var select = document.createElement('select');
      select.setAttribute('data-index', i);
      select.setAttribute('data-col', col);
      select.appendChild(new Option('all', ''));
      Object.keys(values).sort().forEach(function (v) { select.appendChild(new Option(v, v)); });
      select.addEventListener('change', function () { applyFilters(table, bar); });
      label.appendChild(select);
      bar.appendChild(label);
    });
    var input = document.createElement('input');
    input.type = 'search';
    input.placeholder = 'any text';
    input.addEventListener('input', function () { applyFilters(table, bar); });
    bar.appendChild(input);
    var count = document.createElement('span');
    count.className = 'count';
    bar.appendChild(count);
    applyFilters(table, bar);
  }

  // report.html#selftest: sorts and filters the first filterable table and writes what it found
  // into a pre element with id selftest, for the headless-browser test (reports/chromium_test.py).
  function selfTest() {
    var problems = [];
    var table = document.querySelector('table.sortable.filterable');
    if (!table) problems.push('no sortable, filterable table');
    else {
      var heads = table.tHead.rows[0].cells, numeric = -1;
      for (var i = 0; i < heads.length && numeric < 0; i++)
        if (table.tBodies[0].rows.length && table.tBodies[0].rows[0].cells[i].hasAttribute('data-v')) numeric = i;
      if (numeric < 0) problems.push('no numeric column');
      else {
        heads[numeric].click();
        heads[numeric].click();  // twice: descending
        var values = Array.prototype.map.call(table.tBodies[0].rows, function (r) { return cellValue(r, numeric); })
          .filter(function (v) { return typeof v === 'number'; });
        for (var k = 1; k < values.length; k++)
          if (values[k] > values[k - 1]) { problems.push('column ' + numeric + ' not sorted descending'); break; }
      }
      var select = document.querySelector('.filters select[data-col="scheme"]');
      if (!select || select.options.length < 2) problems.push('no scheme filter');
      else {
        var wanted = select.options[1].value;
        select.value = wanted;
        select.dispatchEvent(new Event('change'));
        var index = +select.getAttribute('data-index');
        Array.prototype.forEach.call(table.tBodies[0].rows, function (r) {
          var visible = r.style.display !== 'none';
          if (visible !== (r.cells[index].textContent.trim() === wanted)) problems.push('filter kept a wrong row');
        });
        select.value = '';
        select.dispatchEvent(new Event('change'));
      }
    }
    var out = document.createElement('pre');
    // The first screen and the matrices fit the window (the test opens it 1400 pixels wide): no
    // horizontal scrolling, neither of the page nor inside a matrix's scroll box.
    var wide = [];
    document.querySelectorAll('table.matrix, table.schemes, #overview img.plot').forEach(function (el) {
      var right = el.getBoundingClientRect().right;
      if (right > window.innerWidth) wide.push((el.id || el.className) + ' ends at ' + Math.round(right) + ' px');
    });
    if (document.documentElement.scrollWidth > window.innerWidth) wide.push('the page scrolls sideways');
    if (wide.length) problems.push('wider than the window (' + window.innerWidth + ' px): ' + wide.join(', '));
    out.id = 'selftest';
    out.textContent = (problems.length ? 'selftest failed: ' + problems.join('; ') : 'selftest ok') +
      '\nwindow width: ' + window.innerWidth + ' px' +
      '\nconsole errors: ' + (window.reportErrors || []).length + '\n' + (window.reportErrors || []).join('\n');
    document.body.appendChild(out);
  }

  document.querySelectorAll('table.sortable').forEach(makeSortable);
  document.querySelectorAll('.filters[data-for]').forEach(function (bar) {
    var table = document.getElementById(bar.getAttribute('data-for'));
    if (table) makeFilterable(table, bar);
  });
  // On load, after every other script of the page has run: their errors are counted too.
  if (location.hash === '#selftest') window.addEventListener('load', selfTest);
})();
