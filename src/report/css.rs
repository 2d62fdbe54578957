//! The page's style sheet (inline in `index.html`, no `url(` or `@import`): layout of the
//! first screen's recommendation blocks and table of contents, the folded case parts, the
//! plots with their HTML legends (a row's colour set once as `--c`), the tables and heat maps
//! (whose fill levels `heatmap::css` adds), and the defaults the inline SVGs rely on (white
//! background, sans-serif at 12 px, ink for texts without a fill: `svg_page`).
pub const CSS: &str = "
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0 auto;max-width:1880px;
 padding:0 16px 40px;color:#222;line-height:1.4}
h1{margin:12px 0 2px;font-size:26px}h2{margin:28px 0 4px;border-bottom:2px solid #ccc}
h3{margin:18px 0 6px}
.env{font-size:12px;color:#555;font-family:ui-monospace,monospace;margin:2px 0 6px}
.key{font-size:13px;background:#f6f6f6;padding:6px 10px;border-radius:4px;margin:4px 0}
header p{margin:4px 0}
code{font-family:ui-monospace,monospace;font-size:92%;background:#f2f2f2;padding:0 2px}
.figs{display:grid;grid-template-columns:repeat(auto-fill,minmax(min(100%,640px),1fr));
 gap:0 24px}
figure{margin:12px 0 20px;min-width:0}
.plotrow{display:flex;flex-wrap:wrap;align-items:flex-start;gap:4px 10px}
.plot{flex:1 1 400px;max-width:560px;min-width:0}
.plot svg{display:block;width:100%;height:auto;background:#fff;font-family:sans-serif;
 font-size:12px}
.plot svg text:not([fill]){fill:#3C3C3C}
ul.legend{flex:1 1 150px;list-style:none;margin:6px 0 0;padding:0;font-size:12px;
 display:flex;flex-wrap:wrap;flex-direction:column;align-content:flex-start;gap:1px 12px}
ul.legend li{white-space:nowrap;display:flex;align-items:center;gap:4px;--c:#3c3c3c}
ul.legend li.lh{font-weight:600;color:#444;margin-top:4px}
.ls{display:inline-block;width:26px;border-top:2px solid var(--c);height:0}
.lm{color:var(--c)}
.ls.p2{border-top:0;height:2px;background:repeating-linear-gradient(90deg,var(--c) 0 2px,transparent 2px 5px)}.ls.p3{border-top:0;height:2px;background:repeating-linear-gradient(90deg,var(--c) 0 9px,transparent 9px 12px,var(--c) 12px 14px,transparent 14px 17px)}.ls.p4{border-top:0;height:2px;background:repeating-linear-gradient(90deg,var(--c) 0 14px,transparent 14px 18px)}.ls.p5{border-top:0;height:2px;background:repeating-linear-gradient(90deg,var(--c) 0 9px,transparent 9px 12px,var(--c) 12px 14px,transparent 14px 17px,var(--c) 17px 19px,transparent 19px 22px)}.ls.p6{border-top:0;height:2px;background:repeating-linear-gradient(90deg,var(--c) 0 2px,transparent 2px 9px)}.ls.p7{border-top:0;height:2px;background:repeating-linear-gradient(90deg,var(--c) 0 4px,transparent 4px 6px)}.ls.dash{border-top-style:dashed}.ls.none{border-top-color:transparent}
.lm{display:inline-block;width:12px;text-align:center;font-size:12px;line-height:12px}
figcaption{font-size:13px;color:#444;max-width:900px}
.ptitle{font-size:14px;font-weight:600;color:#3c3c3c;max-width:560px;margin:0 0 2px}
.nodata{max-width:860px;padding:16px 20px;border:1px dashed #bbb;color:#777;background:#fafafa}
.roundoff{color:#333;background:#f4f8fb;border-style:solid;border-color:#c9d8ea}
details{margin:8px 0}summary{cursor:pointer;font-weight:600;margin:6px 0}
.tablewrap{overflow-x:auto;max-width:100%}
table{border-collapse:collapse;font-size:12px;margin:6px 0 14px}
th,td{border:1px solid #ddd;padding:2px 6px;text-align:left;white-space:nowrap}
th{background:#eee;position:sticky;top:0}
td.msg{white-space:normal;min-width:320px}
td.pass{background:#d4efd4}td.fail{background:#f6c8c8;font-weight:600}td.neutral{background:#f3f3f3}
.narrative li{max-width:980px;margin:3px 0}
.scene{border-left:3px solid #ddd;padding-left:12px}
.stability{border-left:3px solid #c9d8ea;padding-left:12px}
td[title]{text-decoration:underline dotted #999;cursor:help}
table.heatmap td{text-align:right;font-variant-numeric:tabular-nums}
table.heatmap td:nth-child(-n+4){text-align:left;background:#fff}
table.heatmap th button{font:inherit;font-weight:600;border:0;background:none;padding:0;
 cursor:pointer;text-decoration:underline dotted #888}
td.hfail,.ramp .hfail{background:repeating-linear-gradient(45deg,#f4c2c2 0 4px,#fff 4px 8px);
 color:#8b0000;font-weight:600}
td.hna,.ramp .hna{background:#e4e4e4;color:#777}
td.gp{box-shadow:inset 0 0 0 2px #1b7f3b}td.gf{box-shadow:inset 0 0 0 3px #000;font-weight:700}
.ramp{font-size:12px;display:flex;flex-wrap:wrap;align-items:center;gap:0;margin:2px 0}
.ramp span{display:inline-block;width:22px;height:12px;border:0}
.ramp .hfail,.ramp .hna{width:auto;height:auto;padding:0 4px;margin:0 4px 0 12px}
section.advice{max-width:1880px}
.toc{font-size:13px;margin:4px 0 8px}.toc .fam{margin-left:14px;white-space:nowrap}
.toc a{margin-right:6px}
.recs{display:grid;grid-template-columns:repeat(auto-fill,minmax(min(100%,380px),1fr));
 gap:8px 14px}
.rec{border:1px solid #ddd;border-radius:4px;padding:4px 8px;font-size:12.5px;
 overflow-wrap:anywhere;min-width:0}
.rec h3{margin:2px 0;font-size:15px}.rec ul{margin:2px 0;padding-left:16px}
.rec li{margin:1px 0}.rec li.none{color:#666}.rec p{margin:2px 0}
.rec .avoid{color:#7a2b00}.refvar{color:#30415d;font-size:12.5px}
.heat .tablewrap{max-height:560px;overflow:auto;border:1px solid #ddd}
.heat table{margin:0}
table.advice{margin:4px 0}table.advice td,table.advice th{padding:1px 6px}
section.advice h2{margin:10px 0 2px}section.advice p{margin:2px 0;font-size:13px}
";
