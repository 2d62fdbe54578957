//! The page's one inline script (no source, no network, no event-handler attributes): it
//! sorts a heat map by the column whose name is clicked (best first, a second click worst
//! first; the `param` column restores registry order), reading the sort keys the Rust code
//! wrote (`data-k`), and, only when the URL hash is `#selftest`, appends a
//! `<pre id="selftest">` with the layout facts the CI browser check reads: the recommendation
//! table's bounding box in page pixels (`advice top= bottom= left= right=`, or `advice none`)
//! and per inline plot its declared line count and its drawn series (`panel <case> <plot>
//! lines=N series=M`).
//!
//! Invariants: the page reads the same without it (the tables are in registry order, every
//! number is in the HTML); it never writes outside the heat-map bodies and the self-test
//! block. It is written without a `<` directly before a letter, so `html::render_check`'s
//! tag tokenizer reads no tag inside it.
pub const SCRIPT: &str = r#"
(function () {
  function key(td) {
    var k = td ? td.getAttribute('data-k') : null;
    return k === null ? 9 : parseFloat(k);
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
            rows.sort(function (a, b) {
              var x = key(a.cells[c]), y = key(b.cells[c]);
              var first = key(a.cells[0]) - key(b.cells[0]);
              if (c === 0) { return first; }
              var xn = x <= 1.5, yn = y <= 1.5;
              if (xn !== yn) { return xn ? -1 : 1; }
              var diff = xn ? d * (x - y) : x - y;
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
  var a = document.querySelector('[data-section="advice"] table');
  if (a) {
    var r = a.getBoundingClientRect();
    out.push('advice top=' + Math.round(r.top + window.scrollY) + ' bottom=' +
      Math.round(r.bottom + window.scrollY) + ' left=' + Math.round(r.left) + ' right=' +
      Math.round(r.right));
  } else {
    out.push('advice none');
  }
  var svgs = document.querySelectorAll('svg[data-lines]');
  for (var s = 0; s < svgs.length; s++) {
    var fig = svgs[s].closest('figure');
    var sec = svgs[s].closest('section');
    out.push('panel ' + (sec ? sec.getAttribute('data-case') : '-') + ' ' +
      (fig ? fig.getAttribute('data-plot') : '-') + ' lines=' +
      svgs[s].getAttribute('data-lines') + ' series=' +
      svgs[s].querySelectorAll('g.series').length);
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
        for bad in ["http", "url(", "@import", "src", "href"] {
            assert!(!SCRIPT.contains(bad), "{bad}");
        }
        assert!(super::super::html::start_tags(SCRIPT).is_empty());
    }
}
