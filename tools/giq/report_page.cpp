#include "report_page.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "giq/base/version.h"
#include "giq/gate/escape.h"
#include "giq/gate/sweep_table.h"
#include "giq/metrics/catalogue.h"

namespace giq::cli {
namespace {

using gate::html_escape;
using nlohmann::json;

const char* kStyle = R"(
body{font-family:system-ui,sans-serif;margin:24px;color:#1a1a1a;background:#fafafa}
h1{margin:0 0 4px}h2{border-bottom:2px solid #ccc;padding-bottom:4px;margin-top:36px}
.meta{color:#666;font-size:13px}
table{border-collapse:collapse;font-size:13px;margin:8px 0}
td,th{border:1px solid #ddd;padding:3px 8px;text-align:left}th{background:#eee}
td.num{text-align:right;font-variant-numeric:tabular-nums}
.PASS{background:#d8f5d8}.WARN{background:#fff1c2}.FAIL{background:#ffd0d0;font-weight:bold}
.UNRESOLVED{background:#e6dcff}.SKIP{background:#eeeeee;color:#555}
.comparison{background:#fff;border:1px solid #ddd;border-radius:6px;padding:12px;margin:16px 0}
.row{display:flex;flex-wrap:wrap;gap:12px}
figure{margin:0}figcaption{font-size:12px;color:#333;margin-top:4px;max-width:320px}
.view{width:320px;height:320px;overflow:hidden;background:#222;position:relative;cursor:grab;touch-action:none}
.view img{position:absolute;left:0;top:0;width:320px;height:320px;object-fit:contain;transform-origin:0 0;
 image-rendering:pixelated;user-select:none;-webkit-user-drag:none}
.scale{width:320px;height:12px;border:1px solid #999;margin-top:4px}
.scale-labels{display:flex;justify-content:space-between;width:320px;font-size:11px;color:#444}
.flipbook .controls{margin:6px 0;font-size:13px}
.plot{max-width:100%;background:#fff;border:1px solid #ddd}
.warning{color:#a00000}
.ab{cursor:pointer}
.hint{font-size:12px;color:#666}
)";

// Synchronised zoom (wheel, about the cursor) and pan (drag) for every .view in a .sync
// group; double-click resets. Flip-books step through frames with a slider or play.
const char* kScript = R"(
document.querySelectorAll('.sync').forEach(function(group){
  var s=1,x=0,y=0;
  var views=group.querySelectorAll('.view');
  function apply(){group.querySelectorAll('.view img').forEach(function(i){
    i.style.transform='translate('+x+'px,'+y+'px) scale('+s+')';});}
  views.forEach(function(v){
    v.addEventListener('wheel',function(e){e.preventDefault();
      var r=v.getBoundingClientRect(),cx=e.clientX-r.left,cy=e.clientY-r.top;
      var n=Math.min(64,Math.max(1,s*(e.deltaY<0?1.25:0.8)));
      x=cx-(cx-x)*n/s;y=cy-(cy-y)*n/s;s=n;if(s===1){x=0;y=0;}apply();},{passive:false});
    var drag=null;
    v.addEventListener('pointerdown',function(e){drag=[e.clientX-x,e.clientY-y];v.setPointerCapture(e.pointerId);});
    v.addEventListener('pointermove',function(e){if(drag){x=e.clientX-drag[0];y=e.clientY-drag[1];apply();}});
    v.addEventListener('pointerup',function(){drag=null;});
    v.addEventListener('dblclick',function(){s=1;x=0;y=0;apply();});
  });
});
document.querySelectorAll('.ab').forEach(function(fig){
  var imgs=fig.querySelectorAll('img'),label=fig.querySelector('.ab-label'),k=1;
  function show(){imgs.forEach(function(img,i){img.style.visibility=(i===k)?'visible':'hidden';});
    label.textContent=imgs[k].alt+' (click or press a key over it: '+imgs[1-k].alt+')';}
  fig.addEventListener('click',function(){k=1-k;show();});
  fig.tabIndex=0;fig.addEventListener('keydown',function(){k=1-k;show();});
  show();
});
document.querySelectorAll('.comparison').forEach(function(cmp){
  var d=cmp.querySelector('.readout-data'),row=cmp.querySelector('.row.sync');if(!d||!row)return;
  var out=cmp.querySelector('.readout'),w=+d.dataset.w,h=+d.dataset.h,labels=JSON.parse(d.dataset.labels),data=null;
  function decode(){data=d.dataset.values.split(',').map(function(b){var s=atob(b),u=new Uint8Array(s.length);
    for(var i=0;i<s.length;i++)u[i]=s.charCodeAt(i);return new Float32Array(u.buffer);});}
  function fmt(v){return isFinite(v)?Number(v.toPrecision(4)).toString():String(v);}
  row.querySelectorAll('.view').forEach(function(v){
    v.addEventListener('pointermove',function(e){
      var img=v.querySelector('img');if(!img)return;
      var r=img.getBoundingClientRect(),k=Math.min(320/w,320/h),ox=(320-w*k)/2,oy=(320-h*k)/2;
      var x=Math.floor(((e.clientX-r.left)/r.width*320-ox)/k),y=Math.floor(((e.clientY-r.top)/r.height*320-oy)/k);
      if(x<0||y<0||x>=w||y>=h){out.textContent='point at an image for its pixel\'s values';return;}
      if(!data)decode();
      var i=y*w+x,parts=[];
      for(var c=0;c<labels.length;){
        var rgb=/ R$/.test(labels[c])&&c+2<labels.length;
        if(rgb){parts.push(labels[c].slice(0,-2)+' ('+fmt(data[c][i])+', '+fmt(data[c+1][i])+', '+fmt(data[c+2][i])+')');c+=3;}
        else{parts.push(labels[c]+' '+fmt(data[c][i]));c+=1;}}
      out.textContent='pixel ('+x+', '+y+'): '+parts.join(' \u00b7 ');});
  });
});
document.querySelectorAll('.flipbook').forEach(function(book){
  var slider=book.querySelector('input[type=range]'),label=book.querySelector('.frame-label');
  var first=parseInt(book.dataset.first,10),step=parseInt(book.dataset.step,10),timer=null;
  function show(k){book.querySelectorAll('.view').forEach(function(v){
    v.querySelectorAll('img').forEach(function(img,i){img.style.visibility=(i===k)?'visible':'hidden';});});
    label.textContent='frame '+(first+k*step);}
  slider.addEventListener('input',function(){show(parseInt(slider.value,10));});
  book.querySelector('button').addEventListener('click',function(){
    if(timer){clearInterval(timer);timer=null;return;}
    timer=setInterval(function(){slider.value=(parseInt(slider.value,10)+1)%(parseInt(slider.max,10)+1);
      show(parseInt(slider.value,10));},1000/12);});
  show(parseInt(slider.value,10));
});
)";

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string hex(double r, double g, double b) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", int(std::lround(r * 255)),
                int(std::lround(g * 255)), int(std::lround(b * 255)));
  return buf;
}

double encode_srgb(double l) {
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}
double decode_srgb(double e) {
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

std::string figure(const Picture& p, const std::string& extra_imgs = "") {
  std::ostringstream s;
  s << "<figure><div class=\"view\">";
  if (extra_imgs.empty())
    s << "<img alt=\"" << html_escape(p.title) << "\" src=\"" << p.data_uri << "\">";
  else
    s << extra_imgs;
  s << "</div>";
  if (p.scale) {
    // Five ticks at fixed fractions of the range; where the range is a percentile of the
    // values, the ends also stand for everything beyond them (the map clips there).
    const bool clipped = p.scale->rule.find("percentile") != std::string::npos;
    s << "<div class=\"scale\" style=\"background:linear-gradient(to right,"
      << colormap_gradient(p.scale->colormap) << ")\"></div><div class=\"scale-labels\">";
    for (int k = 0; k <= 4; ++k) {
      const double v = p.scale->lo + (p.scale->hi - p.scale->lo) * k / 4.0;
      const bool end_clipped = clipped && (k == 4 || (k == 0 && p.scale->lo < 0.0));
      s << "<span>" << (end_clipped ? (k == 0 ? "&le;" : "&ge;") : "") << num(std::abs(v) < 1e-12 * std::abs(p.scale->hi) ? 0.0 : v)
        << "</span>";
    }
    s << "</div>";
  }
  s << "<figcaption>" << html_escape(p.title);
  if (p.scale) {
    s << "<br><span class=\"hint\">";
    if (!p.scale->unit.empty()) s << "unit: " << html_escape(p.scale->unit) << "; ";
    s << "range: " << html_escape(p.scale->rule) << "</span>";
  }
  s << "</figcaption></figure>\n";
  return s.str();
}

void gate_section(std::ostringstream& h, const json& g) {
  h << "<h2>Gate</h2>\n<p>" << (g.value("passed", false) ? "passed" : "<strong>FAILED</strong>")
    << " &mdash; config " << html_escape(g.value("config", ""))
    << "</p>\n<table><tr><th>case</th><th>metric</th><th>value</th><th>bound</th>"
    << "<th>status</th><th>note</th></tr>\n";
  for (const json& o : g.value("outcomes", json::array())) {
    const std::string status = o.value("status", "");
    const bool known = status == "PASS" || status == "WARN" || status == "FAIL" ||
                       status == "UNRESOLVED" || status == "SKIP";
    h << "<tr class=\"" << (known ? status : "") << "\"><td>" << html_escape(o.value("case", ""))
      << "</td><td>" << html_escape(o.value("metric", "")) << "</td><td class=\"num\">"
      << (o.contains("value") && o["value"].is_number() ? num(o["value"]) : "-") << "</td><td>"
      << html_escape(o.value("bound", "")) << "</td><td>" << html_escape(status) << "</td><td>"
      << html_escape(o.value("message", "")) << "</td></tr>\n";
  }
  h << "</table>\n";
}

// One row per comparison: its headline metrics (catalogue order, with unit and direction in
// the header) and the technique's frame time where the score recorded one.
void summary_section(std::ostringstream& h, const std::vector<Comparison>& comparisons) {
  std::vector<const metrics::MetricInfo*> columns;
  for (const metrics::MetricInfo& info : metrics::kMetricCatalogue)
    for (const Comparison& c : comparisons)
      if (std::any_of(c.headline.begin(), c.headline.end(), [&](const auto& m) { return m.first == info.name; })) {
        columns.push_back(&info);
        break;
      }
  const bool timed = std::any_of(comparisons.begin(), comparisons.end(), [](const Comparison& c) { return c.gpu_ms.has_value(); });
  const bool warned = std::any_of(comparisons.begin(), comparisons.end(), [](const Comparison& c) { return !c.warnings.empty(); });
  h << "<h2>Summary</h2>\n<table><tr><th>comparison</th><th>technique</th><th>layer</th>";
  if (timed) h << "<th>GPU ms<br><span class=\"hint\">ms, lower is better</span></th>";
  for (const auto* m : columns)
    h << "<th>" << html_escape(std::string(m->name)) << "<br><span class=\"hint\">" << html_escape(std::string(m->unit)) << ", "
      << (m->better == metrics::Better::Lower ? "lower" : "higher") << " is better</span></th>";
  if (warned) h << "<th>warnings</th>";
  h << "</tr>\n";
  for (const Comparison& c : comparisons) {
    h << "<tr><td>" << html_escape(c.label) << "</td><td>" << html_escape(c.technique) << "</td><td>" << html_escape(c.layer)
      << "</td>";
    if (timed) h << "<td class=\"num\">" << (c.gpu_ms ? num(*c.gpu_ms) : "-") << "</td>";
    for (const auto* m : columns) {
      const auto it = std::find_if(c.headline.begin(), c.headline.end(), [&](const auto& v) { return v.first == m->name; });
      if (it == c.headline.end()) {
        h << "<td class=\"num\">-</td>";
        continue;
      }
      const double v = *it->second.value;
      h << "<td class=\"num" << (it->second.unresolved ? " UNRESOLVED" : "") << "\">" << (std::isinf(v) ? "inf" : num(v))
        << (it->second.unresolved ? " (unresolved)" : "") << "</td>";
    }
    if (warned)
      h << (c.warnings.empty() ? "<td></td>" : "<td class=\"warning\">" + std::to_string(c.warnings.size()) + " warning(s)</td>");
    h << "</tr>\n";
  }
  h << "</table>\n";
}

void comparison_section(std::ostringstream& h, const Comparison& c) {
  h << "<div class=\"comparison\"><h3>" << html_escape(c.technique) << " &mdash; "
    << html_escape(c.label) << "</h3>\n"
    << "<p class=\"meta\">layer " << html_escape(c.layer) << " &middot; " << html_escape(c.source)
    << " &middot; <span class=\"hint\">wheel: zoom, drag: pan, double-click: reset (all images "
       "together)</span></p>\n";
  for (const std::string& w : c.warnings) h << "<p class=\"warning\">warning: " << html_escape(w) << "</p>\n";
  h << "<div class=\"row sync\">\n";
  for (const Picture& p : c.panes) h << figure(p);
  // A/B: the reference and the technique in one place, toggled by a click.
  if (c.panes.size() == 2) {
    h << "<figure class=\"ab\"><div class=\"view\"><img alt=\"" << html_escape(c.panes[0].title) << "\" src=\""
      << c.panes[0].data_uri << "\"><img alt=\"" << html_escape(c.panes[1].title) << "\" src=\"" << c.panes[1].data_uri
      << "\"></div><figcaption>A/B: <span class=\"ab-label\"></span></figcaption></figure>\n";
  }
  for (const Picture& p : c.maps) h << figure(p);
  h << "</div>\n";
  if (c.readout.width > 0) {
    // The values under the pointer, as float32 little-endian in base64, one string a channel.
    json labels = json::array();
    std::string values;
    for (const auto& [label, v] : c.readout.channels) {
      labels.push_back(label);
      if (!values.empty()) values += ',';
      values += gate::base64(std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float)));
    }
    h << "<p class=\"readout hint\">point at an image for its pixel's values</p><div class=\"readout-data\" hidden "
         "data-w=\""
      << c.readout.width << "\" data-h=\"" << c.readout.height << "\" data-labels=\"" << html_escape(labels.dump())
      << "\" data-values=\"" << values << "\"></div>\n";
  } else if (!c.panes.empty()) {
    h << "<p class=\"hint\">no pixel readout: images above " << kReadoutPixels << " pixels are not embedded</p>\n";
  }
  if (!c.technique_frames.empty()) {
    const size_t n = c.technique_frames.size();
    auto frames = [&](const std::vector<std::string>& uris, const std::string& who) {
      std::string s;
      for (size_t i = 0; i < uris.size(); ++i)
        s += "<img alt=\"" + html_escape(who) + " frame " + std::to_string(i) + "\" src=\"" +
             uris[i] + "\">";
      return s;
    };
    h << "<div class=\"flipbook\" data-first=\"" << c.first_frame
      << "\" data-step=\"1\"><h4>Sequence (flicker)</h4>"
      << "<div class=\"controls\"><button type=\"button\">play / pause</button> <input "
         "type=\"range\" min=\"0\" max=\""
      << n - 1 << "\" value=\"" << n - 1
      << "\"> <span class=\"frame-label\"></span></div><div class=\"row sync\">\n"
      << figure({"reference", "", {}}, frames(c.reference_frames, "reference"))
      << figure({c.technique, "", {}}, frames(c.technique_frames, c.technique)) << "</div></div>\n";
  }
  if (!c.metrics.empty()) {
    h << "<table><tr><th>metric</th><th>value</th></tr>\n";
    for (const auto& [k, v] : c.metrics)
      h << "<tr><td>" << html_escape(k) << "</td><td class=\"num\">" << html_escape(v)
        << "</td></tr>\n";
    h << "</table>\n";
  }
  h << "</div>\n";
}

void sweep_section(std::ostringstream& h, const Sweep& s) {
  const std::vector<gate::SweepRow> rows = gate::sweep_rows(s.data, s.source);
  const std::string metric = s.data.value("error_metric", "flip_mean");
  const std::string svg = gate::sweep_svg(rows, metric, true, "error vs GPU time: " + s.source);
  h << "<h3>" << html_escape(s.source)
    << "</h3>\n<img class=\"plot\" alt=\"sweep plot\" src=\"data:image/svg+xml;base64,"
    << gate::base64(svg)
    << "\">\n<table><tr><th>technique</th><th>setting</th><th>default</th><th>GPU ms</th><th>"
    << html_escape(metric) << "</th><th>Pareto front</th></tr>\n";
  for (const auto& r : rows) {
    const auto it = r.metrics.find(metric);
    h << "<tr><td>" << html_escape(r.technique) << "</td><td>"
      << html_escape(gate::setting_label(r.parameters)) << "</td><td>"
      << (r.is_default ? "yes" : "") << "</td><td class=\"num\">"
      << (r.gpu_ms ? num(*r.gpu_ms) : "-") << "</td><td class=\"num\">"
      << (it != r.metrics.end() && it->second ? num(*it->second) : html_escape(r.error))
      << "</td><td>" << (r.on_front ? "yes" : "") << "</td></tr>\n";
  }
  h << "</table>\n";
}

}  // namespace

std::string colormap_gradient(const std::string& colormap) {
  if (colormap == "blue-white-red") {
    // Each half interpolates in linear light between white and the end colour (as giq score's
    // diverging map does); nine stops per half keep the CSS (sRGB) interpolation close.
    const double blue[3] = {59 / 255.0, 76 / 255.0, 192 / 255.0},
                 red[3] = {180 / 255.0, 4 / 255.0, 38 / 255.0};
    std::string s;
    for (int i = -8; i <= 8; ++i) {
      const double t = std::abs(i) / 8.0;
      const double* end = i < 0 ? blue : red;
      double c[3];
      for (int k = 0; k < 3; ++k) c[k] = encode_srgb((1.0 - t) + t * decode_srgb(end[k]));
      s += (s.empty() ? "" : ",") + hex(c[0], c[1], c[2]);
    }
    return s;
  }
  // magma's nine published samples (van der Walt and Smith, matplotlib 1.5).
  return "#000004,#1d1147,#51127c,#822681,#b63679,#e65164,#fb8861,#fec287,#fcfdbf";
}

std::string report_html(const ReportInputs& in, const std::string& title) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
    << html_escape(title) << "</title>\n<style>" << kStyle << "</style></head><body>\n<h1>"
    << html_escape(title) << "</h1>\n<p class=\"meta\">" << html_escape(in.dir.string())
    << " &middot; giq " << html_escape(giq::version()) << "</p>\n";
  for (const std::string& w : in.warnings)
    h << "<p class=\"warning\">not shown: " << html_escape(w) << "</p>\n";
  if (in.gate) gate_section(h, *in.gate);
  if (!in.comparisons.empty()) summary_section(h, in.comparisons);
  std::string scene;
  for (const Comparison& c : in.comparisons) {
    if (c.scene != scene) h << "<h2>Scene " << html_escape(c.scene) << "</h2>\n", scene = c.scene;
    comparison_section(h, c);
  }
  if (!in.sweeps.empty() || !in.plots.empty()) h << "<h2>Speed and accuracy</h2>\n";
  for (const Sweep& s : in.sweeps) sweep_section(h, s);
  for (const Picture& p : in.plots)
    h << "<h3>" << html_escape(p.title) << "</h3>\n<img class=\"plot\" alt=\""
      << html_escape(p.title) << "\" src=\"" << p.data_uri << "\">\n";
  h << "<script>" << kScript << "</script>\n</body></html>\n";
  return h.str();
}

}  // namespace giq::cli
