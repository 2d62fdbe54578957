//! The page's one inline script (no source, no network, no event-handler attributes): it
//! sorts a heat map by the column whose name is clicked (best first, a second click worst
//! first; the `param` column restores registry order), reading the values the cells show
//! (their fill class says a value is on its column's scale, `hfail`/`hna` failed, null or n/a;
//! the first cell's `data-k` is the registry position), and, only when the URL hash is `#selftest`, appends a
//! `<pre id="selftest">` with the layout facts the CI browser check reads: the recommendation
//! table's bounding box in page pixels (`advice top= bottom= left= right=`, or `advice none`),
//! each case's recommendation block (`rec <case> top= bottom= height=`), the page's size
//! (`page height= width= viewport=WxH svgs=`, the document's scroll height and width) and per
//! inline plot its declared line count, its drawn series and how many of its lines repeat
//! an earlier line's colour and pattern (`panel <case> <plot> lines=N series=M same=K`).
//!
//! Invariants: the page reads the same without it (the tables are in registry order, every
//! number is in the HTML); it never writes outside the heat-map bodies and the self-test
//! block. It is written without a `<` directly before a letter, so `html::render_check`'s
//! tag tokenizer reads no tag inside it.
pub const SCRIPT: &str = r#"
(function () {
  // A cell's sort key [group, value]: 0 a coloured value (negated where larger is better),
  // 1 a value off its column's scale, 2 failed, 3 null, 4 n/a; a cell with data-k (the
  // row's registry position) is group 0 with that value.
  function key(td, larger) {
    if (!td) { return [9, 0]; }
    var k = td.getAttribute('data-k');
    if (k !== null) { return [0, parseFloat(k)]; }
    var cls = ' ' + td.className + ' ';
    if (cls.indexOf(' hfail ') !== -1) { return [2, 0]; }
    if (cls.indexOf(' hna ') !== -1) { return [td.textContent.indexOf('null') !== -1 ? 3 : 4, 0]; }
    var v = parseFloat(td.textContent.replace(/[^0-9eE.+-]/g, ''));
    if (isNaN(v)) { return [4, 0]; }
    if (/ c[0-9]+ /.test(cls)) { return [0, larger ? -v : v]; }
    return [1, 0];
  }
  var tables = document.querySelectorAll('table.heatmap');
  for (var t = 0; t < tables.length; t++) {
    (function (table) {
      var dir = {};
      var heads = table.tHead.rows[0].cells;
      for (var h = 0; h < heads.length; h++) {
        (function (th) {
          var b = th.querySelector('button');
          if (!b) { return; }
          b.addEventListener('click', function () {
            var c = parseInt(th.getAttribute('data-col'), 10);
            var body = table.tBodies[0];
            var rows = Array.prototype.slice.call(body.rows);
            var d = dir[c] = (dir[c] === 1 ? -1 : 1);
            var larger = th.textContent.indexOf('larger better') !== -1;
            rows.sort(function (a, b) {
              var x = key(a.cells[c], larger), y = key(b.cells[c], larger);
              var first = key(a.cells[0])[1] - key(b.cells[0])[1];
              if (c === 0) { return first; }
              var xn = x[0] !== 2 && x[0] !== 3 && x[0] !== 4 && x[0] !== 9;
              var yn = y[0] !== 2 && y[0] !== 3 && y[0] !== 4 && y[0] !== 9;
              if (xn !== yn) { return xn ? -1 : 1; }
              var diff = xn ? d * (x[0] - y[0] || x[1] - y[1]) : x[0] - y[0];
              return diff !== 0 ? diff : first;
            });
            for (var i = 0; i < rows.length; i++) { body.appendChild(rows[i]); }
          });
        })(heads[h]);
      }
    })(tables[t]);
  }
  if (location.hash !== '#selftest') { return; }
  var out = [];
  var a = document.querySelector('[data-section="advice"]');
  if (a) {
    var r = a.getBoundingClientRect();
    out.push('advice top=' + Math.round(r.top + window.scrollY) + ' bottom=' +
      Math.round(r.bottom + window.scrollY) + ' left=' + Math.round(r.left) + ' right=' +
      Math.round(r.right));
  } else {
    out.push('advice none');
  }
  var recs = document.querySelectorAll('[data-rec]');
  for (var q = 0; q !== recs.length; q++) {
    var b = recs[q].getBoundingClientRect();
    out.push('rec ' + recs[q].getAttribute('data-rec') + ' top=' +
      Math.round(b.top + window.scrollY) + ' bottom=' + Math.round(b.bottom + window.scrollY) +
      ' height=' + Math.round(b.height));
  }
  var de = document.documentElement;
  out.push('page height=' + Math.max(de.scrollHeight, document.body.scrollHeight) +
    ' width=' + Math.max(de.scrollWidth, document.body.scrollWidth) + ' viewport=' +
    window.innerWidth + 'x' + window.innerHeight + ' svgs=' +
    document.querySelectorAll('svg').length);
  var svgs = document.querySelectorAll('svg[data-lines]');
  for (var s = 0; s < svgs.length; s++) {
    var fig = svgs[s].closest('figure');
    var sec = svgs[s].closest('section');
    var seen = {};
    var same = 0;
    var polys = svgs[s].querySelectorAll('g.series polyline, g.series path');
    for (var k = 0; k !== polys.length; k++) {
      var look = polys[k].getAttribute('stroke') + ' ' +
        (polys[k].getAttribute('stroke-dasharray') || 'solid');
      if (seen[look]) { same++; }
      seen[look] = true;
    }
    out.push('panel ' + (sec ? sec.getAttribute('data-case') : '-') + ' ' +
      (fig ? fig.getAttribute('data-plot') : '-') + ' lines=' +
      svgs[s].getAttribute('data-lines') + ' series=' +
      svgs[s].querySelectorAll('g.series').length + ' same=' + same);
  }
  var pre = document.createElement('pre');
  pre.id = 'selftest';
  pre.textContent = out.join('\n');
  document.body.appendChild(pre);
})();
"#;

#[cfg(test)]
mod tests {
    use super::*;

    /// The script holds no tag the page's checker would read (no `<` before a letter) and
    /// refers to nothing outside the page.
    #[test]
    fn script_is_inert_to_the_checker() {
        let b = SCRIPT.as_bytes();
        assert!(
            !b.windows(2)
                .any(|w| w[0] == b'<' && (w[1].is_ascii_alphabetic() || w[1] == b'/'))
        );
        // No backtick either: the page holds no literal markdown.
        for bad in ["http", "url(", "@import", "src", "href", "`"] {
            assert!(!SCRIPT.contains(bad), "{bad}");
        }
        assert!(super::super::html::start_tags(SCRIPT).is_empty());
    }
}
