#include "views/submit_form.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "io/xml_escape.hpp"

namespace rupture::server {

using rupture::io::xmlEscape;
using namespace html;

namespace {

/// How a field is typed in: the script parses each kind back to JSON.
std::string kindOf(const Json& node) {
  if (node.contains("enum")) return "enum";
  std::string type;
  if (node.contains("type")) {
    if (node["type"].is_string()) type = node["type"].get<std::string>();
    else if (node["type"].is_array())
      for (const auto& t : node["type"])
        if (t.is_string() && t != "null") type = t.get<std::string>();
  }
  if (type == "number" || type == "integer" || type == "string" || type == "boolean") return type;
  if (type == "array" && node.contains("items") && node["items"].is_object()) {
    const std::string item = node["items"].value("type", "");
    if (item == "number" || item == "integer") return "numbers";
  }
  return "json";
}

/// The shortest text that reads back to the same number, exponent without "+" or leading zeros
/// (4e9, not 4000000000.0; 2.865e12).
std::string shortest(const Json& v) {
  if (!v.is_number_float()) return v.dump();
  const double x = v.get<double>();
  char buffer[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  std::string text = buffer;
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent[0] == '-' || exponent[0] == '+' ? 1 : 0);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e) + (negative ? "e-" : "e") + exponent;
}

/// The value as the form shows it: numbers in their shortest text, lists comma-separated.
std::string shown(const Json& v, const std::string& kind) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (kind == "numbers" && v.is_array()) {
    std::string out;
    for (const auto& x : v) out += (out.empty() ? "" : ", ") + shortest(x);
    return out;
  }
  return shortest(v);
}

/// `value` at the dotted `path` in `root`, making the objects on the way (the script's setPath).
void setPath(Json& root, const std::string& path, const Json& value) {
  Json* node = &root;
  std::size_t from = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; from = dot + 1, dot = path.find('.', from)) {
    Json& next = (*node)[path.substr(from, dot - from)];
    if (!next.is_object()) next = Json::object();
    node = &next;
  }
  (*node)[path.substr(from)] = value;
}

struct FormBuilder {
  std::string html;
  std::vector<std::string> sweepable;  // leaf paths a sweep may vary
  Json inputs = Json::object();        // what the script posts when nothing is changed

  void fields(const Json& schema, const Json& start, const std::string& prefix, int depth) {
    if (!schema.is_object() || !schema.contains("properties") || depth > 5) return;
    const Json required = schema.value("required", Json::array());
    for (const auto& [key, sub] : schema["properties"].items()) {
      if (key == "scenario" || key == "description") continue;
      const std::string path = prefix.empty() ? key : prefix + "." + key;
      const bool isRequired = std::find(required.begin(), required.end(), key) != required.end();
      const bool given = start.is_object() && start.contains(key);
      const std::string title = sub.value("title", key) + (isRequired ? " *" : "");
      if (sub.is_object() && sub.contains("properties")) {
        // A nested object: open when the starting spec has it, else folded away (and sent only
        // if something in it is filled in).
        html += std::string("<details") + (given ? " open" : "") + "><summary><code>" + xmlEscape(path) + "</code> " +
                xmlEscape(sub.value("description", "")) + "</summary><div class=\"group\">";  // whole: a cut could split an entity
        fields(sub, given ? start[key] : Json(), path, depth + 1);
        html += "</div></details>\n";
        continue;
      }
      const std::string kind = kindOf(sub);
      // Only the starting spec fills a field. A schema default is shown, not filled in: sent, it
      // would be a choice nobody made, and it may not apply to the chosen model or shape at all
      // (bond_gap on a lattice, a crack count on a plain hole); left empty, the server applies it
      // where it belongs.
      const Json value = given ? start[key] : Json();
      const std::string placeholder = sub.contains("default") ? "default " + shown(sub["default"], kind) : std::string();
      if (!value.is_null() && !(value.is_string() && value.get<std::string>().empty())) setPath(inputs, path, value);
      const std::string id = "in-" + path;
      html += "<div class=\"field\"><label for=\"" + xmlEscape(id) + "\" title=\"" +
              xmlEscape(sub.value("description", "")) + "\"><code>" + xmlEscape(path) + "</code>" +
              (isRequired ? " *" : "") + "</label> ";
      const std::string attributes = "id=\"" + xmlEscape(id) + "\" data-path=\"" + xmlEscape(path) +
                                     "\" data-kind=\"" + kind + "\"";
      if (kind == "enum" || kind == "boolean") {
        html += "<select " + attributes + "><option value=\"\">" + xmlEscape(placeholder.empty() ? "" : "(" + placeholder + ")") +
                "</option>";
        const Json options = kind == "enum" ? sub["enum"] : Json::array({true, false});
        for (const auto& o : options) {
          const std::string text = o.is_string() ? o.get<std::string>() : o.dump();
          html += "<option value=\"" + xmlEscape(text) + "\"" + (value == o ? " selected" : "") + ">" + xmlEscape(text) +
                  "</option>";
        }
        html += "</select>";
      } else if (kind == "json") {
        html += "<textarea rows=\"2\" cols=\"60\" " + attributes + " placeholder=\"" +
                xmlEscape(placeholder.empty() ? "JSON" : placeholder) + "\">" +
                xmlEscape(value.is_null() ? "" : value.dump()) + "</textarea>";
      } else {
        html += "<input size=\"24\" " + attributes + " value=\"" + xmlEscape(shown(value, kind)) + "\"" +
                (!placeholder.empty() ? " placeholder=\"" + xmlEscape(placeholder) + "\""
                 : kind == "numbers"  ? std::string(" placeholder=\"a, b, ...\"")
                                      : std::string()) +
                ">";
      }
      if (const std::string unit = schemaUnit(sub); !unit.empty() && unit != "1")
        html += " <span class=\"unit\">" + xmlEscape(unit) + "</span>";
      html += " <span class=\"hint\">" + xmlEscape(sub.value("title", "")) + "</span></div>\n";
      if (kind != "json") sweepable.push_back(path);
    }
  }
};

// Builds the request from the form; Preview posts it as a dry run (run count, elements, memory, time),
// Submit posts it and shows the job or the problem that names the field.
constexpr const char* kSubmitScript = R"js(
const form=document.getElementById('submit-form');const out=document.getElementById('form-error');
const token=document.getElementById('token');token.value=sessionStorage.getItem('rupture-token')||'';
function setPath(o,path,v){const ks=path.split('.');let c=o;for(let i=0;i<ks.length-1;i++){
 if(typeof c[ks[i]]!=='object'||c[ks[i]]===null||Array.isArray(c[ks[i]]))c[ks[i]]={};c=c[ks[i]];}c[ks[ks.length-1]]=v;}
function number(text,path){const v=Number(text);if(text===''||!isFinite(v))throw new Error(path+': "'+text+'" is not a number');return v;}
function parse(el){const t=el.value.trim(),k=el.dataset.kind,p=el.dataset.path;if(t==='')return undefined;
 if(k==='number')return number(t,p);
 if(k==='integer'){const v=number(t,p);if(!Number.isInteger(v))throw new Error(p+': "'+t+'" is not an integer');return v;}
 if(k==='boolean')return t==='true';
 if(k==='numbers')return t.split(',').map(s=>number(s.trim(),p));
 if(k==='json'){try{return JSON.parse(t);}catch(e){throw new Error(p+': not valid JSON');}}
 if(k==='enum'){const v=Number(t);return isFinite(v)&&String(v)===t?v:t;}
 return t;}
function list(text){return text.split(',').map(s=>s.trim()).filter(s=>s!=='').map(s=>{const v=Number(s);return isFinite(v)?v:s;});}
function build(){const body=JSON.parse(form.dataset.extra||'{}');body.inputs=body.inputs||{};
 for(const el of form.querySelectorAll('[data-path]')){const v=parse(el);if(v!==undefined)setPath(body.inputs,el.dataset.path,v);}
 const name=document.getElementById('job-name').value.trim();if(name)body.name=name;
 const sweep={};for(const row of form.querySelectorAll('.sweep-row')){const p=row.querySelector('select').value,
  v=row.querySelector('input').value;if(p&&v.trim())sweep[p]=list(v);}
 if(Object.keys(sweep).length){body.sweep=sweep;const m=document.getElementById('sweep-mode').value;if(m)body.sweep_mode=m;}
 const n=parseInt(document.getElementById('replicates').value,10);
 if(n>1)body.replicates={count:n,vary:document.getElementById('vary').value.trim()};
 return body;}
function headers(){const t=token.value.trim();if(t)sessionStorage.setItem('rupture-token',t);else sessionStorage.removeItem('rupture-token');
 const h={'Content-Type':'application/json','Accept':'application/json'};if(t)h.Authorization='Bearer '+t;return h;}
function mark(d){for(const el of form.querySelectorAll('.bad'))el.classList.remove('bad');
 if(d.field){const el=form.querySelector('[data-path="'+CSS.escape(d.field)+'"]');if(el){el.classList.add('bad');el.focus();}}}
function bytes(b){if(b===null||b===undefined)return 'not estimated';const u=['B','KiB','MiB','GiB','TiB'];let k=0;
 while(b>=1024&&k<u.length-1){b/=1024;k++;}return (k?b.toPrecision(3):b)+' '+u[k];}
function duration(s){if(s===null||s===undefined)return 'not estimated';return fq(s,'s');}
function count(n){return n===null||n===undefined?'not estimated':Number(n).toLocaleString('en');}
const preview=document.getElementById('preview');const picture=document.getElementById('preview-picture');
const caption=document.getElementById('preview-caption');let pictured=null;
function showPicture(p,asked){if(!asked){caption.textContent=pictured===null?'Press Preview to draw the sample.':
  (pictured===JSON.stringify(build())?caption.textContent:'The picture is of the form as it was when Preview was pressed; press Preview to draw it again.');return;}
 if(p&&p.available){picture.src=p.href;picture.hidden=false;picture.alt=(p.caption||[]).join('; ');
  caption.textContent=(p.note?p.note+'. ':'')+(p.caption||[]).join('; ')+' (built in '+duration(p.build_s)+
   (p.sample_from_cache?', the sample read from the cache':'')+')';}
 else{picture.hidden=true;picture.removeAttribute('src');caption.textContent='No picture: '+(p?p.reason:'not drawn');}}
async function showPreview(withPicture){let body;try{body=build();}catch(x){preview.textContent=x.message;return;}
 preview.textContent=withPicture?'building the sample...':'estimating...';let r,d={};
 try{r=await fetch(form.dataset.action+'?dry_run=true'+(withPicture?'&picture=true':''),{method:'POST',headers:headers(),body:JSON.stringify(body)});d=await r.json();}
 catch(x){preview.textContent='no answer from the server: '+x;return;}
 mark(d);if(r.status!==200){preview.textContent=(d.detail||('HTTP '+r.status))+(d.field?' (field: '+d.field+')':'');return;}
 const e=d.elements||{},rows=[['Runs',d.runs+(d.replicates>1?' ('+d.sweep_points+' points x '+d.replicates+' replicates)':'')],
  ['Elements per run',e.min===e.max?count(e.max):count(e.min)+' to '+count(e.max)],
  ['Memory per run (largest)',bytes(d.memory_bytes)+(d.max_run_memory_bytes?' of '+bytes(d.max_run_memory_bytes)+' allowed':'')],
  ['Time steps per run (most)',count(d.steps)],
  ['Estimated time',d.estimated_wall_s===null?'not estimated (no cost model for this scenario)':
   duration(d.estimated_wall_s)+' for the job'+(d.runs>1?', '+duration(d.estimated_run_s)+' for its longest run':'')+
   ' (a rough estimate: '+(d.cost_model?d.cost_model.uncertainty:'')+')'],
  ['Queue',d.queue.fits_now?'room for it now':'full: the job would be refused until runs finish']];
 if(withPicture)rows.push(['Picture',d.picture&&d.picture.available?count(d.picture.elements)+' '+d.picture.elements_name+
  (d.picture.plate_nodes?' and '+count(d.picture.plate_nodes)+' plate nodes':'')+' built, as the run builds them':
  'not drawn: '+(d.picture?d.picture.reason:'')]);
 preview.replaceChildren();const t=document.createElement('table');t.id='preview-table';
 for(const [k,v] of rows){const tr=t.insertRow();tr.insertCell().textContent=k;tr.insertCell().textContent=v;}
 preview.appendChild(t);if(withPicture)pictured=JSON.stringify(body);showPicture(d.picture,withPicture);}
document.getElementById('preview-button').addEventListener('click',()=>{clearTimeout(pending);showPreview(true);});
// A field change re-estimates at once but draws nothing: a sample costs a run's first stage to build.
let pending;form.addEventListener('change',()=>{clearTimeout(pending);pending=setTimeout(()=>showPreview(false),600);});
showPreview(true);
form.addEventListener('submit',async e=>{e.preventDefault();out.textContent='';
 let body;try{body=build();}catch(x){out.textContent=x.message;return;}
 let r,d={};try{r=await fetch(form.dataset.action,{method:'POST',headers:headers(),body:JSON.stringify(body)});d=await r.json();}
 catch(x){out.textContent='no answer from the server: '+x;return;}
 if(r.status===201){location.href='/jobs/'+encodeURIComponent(d.jobID)+'?f=html';return;}
 out.textContent=(d.detail||('HTTP '+r.status))+(d.field?' (field: '+d.field+')':'');mark(d);});
)js";

/// The form for `process`, filled from `start` (empty: the schema's first example).
FormBuilder buildForm(const Json& schema, const Json& start) {
  Json inputs = start;
  if (!inputs.is_object() || inputs.empty()) {
    inputs = Json::object();
    if (schema.contains("examples") && schema["examples"].is_array() && !schema["examples"].empty())
      inputs = schema["examples"][0];
  }
  FormBuilder form;
  form.fields(schema, inputs, "", 0);
  return form;
}

/// A sweep value the form's value list gives back unchanged: a number, or a string the script
/// will not read as a number, without commas or edge spaces.
bool listable(const Json& v) {
  if (v.is_number()) return true;
  if (!v.is_string()) return false;
  const std::string t = v.get<std::string>();
  if (t.empty() || t.find(',') != std::string::npos || t.front() == ' ' || t.back() == ' ') return false;
  char* end = nullptr;
  std::strtod(t.c_str(), &end);
  return end != t.c_str() + t.size();
}

/// What the form's job part starts from when opened from a job's request ("Submit a variant"): the
/// sweep rows, mode, replicates and name, and the members it has no field for, sent as they were.
struct JobPart {
  std::vector<std::pair<std::string, std::string>> sweepRows;  // path, values as typed
  Json sweep = Json::object();                                 // the same, as the script posts it
  std::string mode;  // "" leaves it to the server (grid)
  int replicates = 1;
  std::string vary, name;
  Json extra = Json::object();
};

/// The members of `start` the form has no field for (`formed`: what its fields post), e.g. a
/// description: a variant sends them as they were.
Json unformed(const Json& start, const Json& formed) {
  Json kept = Json::object();
  for (const auto& [key, value] : start.items()) {
    const auto f = formed.find(key);
    if (f == formed.end()) kept[key] = value;
    else if (value.is_object() && f->is_object())
      if (Json inner = unformed(value, *f); !inner.empty()) kept[key] = std::move(inner);
  }
  return kept;
}

/// The dotted paths of what a variant keeps without a field, for the page's note: each member, and
/// within "inputs" each leaf.
void keptPaths(const Json& kept, const std::string& prefix, std::string& out) {
  for (const auto& [key, value] : kept.items()) {
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object() && !value.empty() && (prefix.empty() ? key == "inputs" : true)) keptPaths(value, path, out);
    else out += (out.empty() ? "" : ", ") + path;
  }
}

/// `formed`: what the form's fields post of the request's inputs.
JobPart jobPartOf(const Json& request, bool seeded, const Json& formed) {
  JobPart part;
  part.vary = seeded ? "sample.seed" : "";
  if (!request.is_object()) return part;
  if (const auto in = request.find("inputs"); in != request.end() && in->is_object())
    if (Json kept = unformed(*in, formed); !kept.empty()) part.extra["inputs"] = std::move(kept);
  bool sweepListable = true;
  if (const auto sw = request.find("sweep"); sw != request.end() && sw->is_object()) {
    for (const auto& [path, values] : sw->items()) {
      if (!values.is_array() || values.empty()) sweepListable = false;
      else
        for (const auto& v : values) sweepListable = sweepListable && listable(v);
    }
    if (sweepListable) {
      for (const auto& [path, values] : sw->items()) {
        std::string text;
        for (const auto& v : values) text += (text.empty() ? "" : ", ") + (v.is_string() ? v.get<std::string>() : shortest(v));
        part.sweepRows.emplace_back(path, text);
      }
      part.sweep = *sw;
    }
  }
  for (const auto& [key, value] : request.items()) {
    if (key == "inputs") continue;
    if (key == "name" && value.is_string()) part.name = value.get<std::string>();
    else if (key == "sweep_mode" && value.is_string() && sweepListable && !part.sweepRows.empty())
      part.mode = value.get<std::string>();
    else if (key == "sweep" && sweepListable) continue;
    else if (key == "replicates" && value.is_object() && value.value("count", Json()).is_number_integer() &&
             value["count"].get<int>() > 1 && value.value("vary", Json()).is_string() && value.size() == 2) {
      part.replicates = value["count"].get<int>();
      part.vary = value["vary"].get<std::string>();
    } else {
      part.extra[key] = value;  // no field for it (refine, an unlistable sweep, ...): sent as it was
    }
  }
  return part;
}

bool hasSeed(const FormBuilder& form) {
  return std::find(form.sweepable.begin(), form.sweepable.end(), "sample.seed") != form.sweepable.end();
}

}  // namespace

Json formInputs(const Json& process, const Json& start) {
  return buildForm(process.value("inputsSchema", Json::object()), start).inputs;
}

Json formRequest(const Json& process, const Json& request) {
  const Json inputs = request.is_object() ? request.value("inputs", Json::object()) : Json::object();
  const FormBuilder form = buildForm(process.value("inputsSchema", Json::object()), inputs);
  const JobPart part = jobPartOf(request, hasSeed(form), form.inputs);
  Json body = part.extra;
  Json posted = body.value("inputs", Json::object());  // the kept members, then the fields over them
  for (const auto& [key, value] : form.inputs.items()) {
    if (value.is_object() && posted.contains(key) && posted[key].is_object()) posted[key].update(value, true);
    else posted[key] = value;
  }
  body["inputs"] = posted;
  if (!part.name.empty()) body["name"] = part.name;
  if (!part.sweep.empty()) {
    body["sweep"] = part.sweep;
    if (!part.mode.empty()) body["sweep_mode"] = part.mode;
  }
  if (part.replicates > 1) body["replicates"] = {{"count", part.replicates}, {"vary", part.vary}};
  return body;
}

HtmlPage processHtml(const Json& process, const Json& start, const Json& request) {
  const std::string id = process.value("id", "");
  const Json schema = process.value("inputsSchema", Json::object());
  const FormBuilder form = buildForm(schema, start);
  const JobPart part = jobPartOf(request, hasSeed(form), form.inputs);

  std::string c = "<p>" + esc(process.value("description", Json(""))) + "</p>\n"
                  "<h2>Submit a job</h2><p>The form starts from " +
                  std::string(start.is_object() && !start.empty() ? "the job it was opened from"
                                                                  : "the scenario's example") +
                  "; an empty field is left to the server, which applies the default shown in it where it applies to the "
                  "chosen model or shape. Units are SI. "
                  "The same request as JSON: <code>POST /processes/" + xmlEscape(id) +
                  "/execution</code> (docs/server.md).</p>"
                  "<form id=\"submit-form\" data-action=\"" + href("/processes/" + id + "/execution") + "\"" +
                  (part.extra.empty() ? std::string() : " data-extra=\"" + xmlEscape(part.extra.dump()) + "\"") + ">\n" +
                  form.html +
                  "<h3>Sweep</h3><p class=\"hint\">Each row varies one field over a list of values "
                  "(comma-separated, e.g. <code>1e5, 1e6, 1e7</code>); grid runs every combination, zip pairs the "
                  "lists.</p>";
  // Three rows, or one more than the job it was opened from sweeps.
  const std::size_t sweepRows = std::max<std::size_t>(3, part.sweepRows.size() + 1);
  for (std::size_t row = 0; row < sweepRows; ++row) {
    const std::string chosen = row < part.sweepRows.size() ? part.sweepRows[row].first : "";
    c += "<div class=\"sweep-row\"><select aria-label=\"swept field\"><option value=\"\"></option>";
    std::vector<std::string> options = form.sweepable;
    if (!chosen.empty() && std::find(options.begin(), options.end(), chosen) == options.end()) options.push_back(chosen);
    for (const std::string& path : options)
      c += "<option" + std::string(path == chosen ? " selected" : "") + ">" + xmlEscape(path) + "</option>";
    c += "</select> <input size=\"40\" aria-label=\"values\" placeholder=\"values, comma-separated\" value=\"" +
         xmlEscape(row < part.sweepRows.size() ? part.sweepRows[row].second : "") + "\"></div>\n";
  }
  auto modeOption = [&](const std::string& value, const std::string& label) {
    return "<option value=\"" + value + "\"" + (part.mode == value ? " selected" : "") + ">" + label + "</option>";
  };
  c += "<p>Mode <select id=\"sweep-mode\">" + modeOption("", "grid (the default)") + modeOption("grid", "grid") +
       modeOption("zip", "zip") + "</select></p>"
       "<h3>Replicates</h3><p>Runs per sweep point <input id=\"replicates\" size=\"4\" value=\"" +
       std::to_string(part.replicates) + "\"> varying <input id=\"vary\" size=\"20\" value=\"" + xmlEscape(part.vary) +
       "\"> <span class=\"hint\">(an integer field; each replicate adds 1)</span></p>";
  if (!part.extra.empty()) {
    std::string kept;
    keptPaths(part.extra, "", kept);
    c += "<p class=\"hint\" id=\"kept\">Kept from the job as it was asked, with no field here: <code>" + xmlEscape(kept) +
         "</code></p>";
  }
  c += "<h3>Job</h3><p>Name <input id=\"job-name\" size=\"40\" value=\"" + xmlEscape(part.name) + "\"> Token <input id=\"token\" type=\"password\" "
       "autocomplete=\"off\" size=\"24\"> <span class=\"hint\">(only if the server has one; kept for this "
       "browser session)</span></p>"
       "<h3>Preview</h3><p class=\"hint\">What the job would be, checked as a submission is but not queued: its runs, "
       "elements, memory and an estimated time (<code>POST .../execution?dry_run=true</code>), updated as you change a "
       "field; and a picture of the first run's sample, plate or tank, built by the run's own builder "
       "(<code>&amp;picture=true</code>), drawn as the form opens and when you press Preview.</p>"
       "<p><button type=\"button\" id=\"preview-button\">Preview</button></p>"
       "<div id=\"preview\" role=\"status\"></div>"
       "<figure id=\"preview-figure\"><img id=\"preview-picture\" hidden alt=\"the discretised sample\">"
       "<figcaption id=\"preview-caption\" class=\"hint\"></figcaption></figure>"
       "<p><button id=\"submit\">Submit</button> <span class=\"error\" id=\"form-error\" "
       "role=\"alert\"></span></p></form>\n";
  std::string rows;
  inputRows(schema, "", rows);
  c += "<details><summary>The inputs as a table</summary><table><tr><th>Field (* required)</th><th>Type</th>"
       "<th>Unit</th><th>Description</th></tr>" + rows + "</table></details>";
  // The preview's times written as every other number a person reads (numberScript's fq).
  return page(id + ": " + process.value("title", ""), c, numberScript() + kSubmitScript);
}

}  // namespace rupture::server
