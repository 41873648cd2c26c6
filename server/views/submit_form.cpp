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
                xmlEscape(sub.value("description", "")).substr(0, 160) + "</summary><div class=\"group\">";
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

// Builds the request from the form and posts it; shows the job or the problem that names the field.
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
form.addEventListener('submit',async e=>{e.preventDefault();out.textContent='';
 for(const el of form.querySelectorAll('.bad'))el.classList.remove('bad');
 const body={inputs:{}};
 try{for(const el of form.querySelectorAll('[data-path]')){const v=parse(el);if(v!==undefined)setPath(body.inputs,el.dataset.path,v);}}
 catch(x){out.textContent=x.message;return;}
 const name=document.getElementById('job-name').value.trim();if(name)body.name=name;
 const sweep={};for(const row of form.querySelectorAll('.sweep-row')){const p=row.querySelector('select').value,
  v=row.querySelector('input').value;if(p&&v.trim())sweep[p]=list(v);}
 if(Object.keys(sweep).length){body.sweep=sweep;body.sweep_mode=document.getElementById('sweep-mode').value;}
 const n=parseInt(document.getElementById('replicates').value,10);
 if(n>1)body.replicates={count:n,vary:document.getElementById('vary').value.trim()};
 const t=token.value.trim();if(t)sessionStorage.setItem('rupture-token',t);else sessionStorage.removeItem('rupture-token');
 const headers={'Content-Type':'application/json','Accept':'application/json'};if(t)headers.Authorization='Bearer '+t;
 let r,d={};try{r=await fetch(form.dataset.action,{method:'POST',headers,body:JSON.stringify(body)});d=await r.json();}
 catch(x){out.textContent='no answer from the server: '+x;return;}
 if(r.status===201){location.href='/jobs/'+encodeURIComponent(d.jobID)+'?f=html';return;}
 out.textContent=(d.detail||('HTTP '+r.status))+(d.field?' (field: '+d.field+')':'');
 if(d.field){const el=form.querySelector('[data-path="'+CSS.escape(d.field)+'"]');if(el){el.classList.add('bad');el.focus();}}});
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

}  // namespace

Json formInputs(const Json& process, const Json& start) {
  return buildForm(process.value("inputsSchema", Json::object()), start).inputs;
}

HtmlPage processHtml(const Json& process, const Json& start) {
  const std::string id = process.value("id", "");
  const Json schema = process.value("inputsSchema", Json::object());
  const FormBuilder form = buildForm(schema, start);

  std::string c = "<p>" + esc(process.value("description", Json(""))) + "</p>\n"
                  "<h2>Submit a job</h2><p>The form starts from " +
                  std::string(start.is_object() && !start.empty() ? "the job it was opened from"
                                                                  : "the scenario's example") +
                  "; an empty field is left to the server, which applies the default shown in it where it applies to the "
                  "chosen model or shape. Units are SI. "
                  "The same request as JSON: <code>POST /processes/" + xmlEscape(id) +
                  "/execution</code> (docs/server.md).</p>"
                  "<form id=\"submit-form\" data-action=\"" + href("/processes/" + id + "/execution") + "\">\n" +
                  form.html +
                  "<h3>Sweep</h3><p class=\"hint\">Each row varies one field over a list of values "
                  "(comma-separated, e.g. <code>1e5, 1e6, 1e7</code>); grid runs every combination, zip pairs the "
                  "lists.</p>";
  for (int row = 0; row < 3; ++row) {
    c += "<div class=\"sweep-row\"><select aria-label=\"swept field\"><option value=\"\"></option>";
    for (const std::string& path : form.sweepable) c += "<option>" + xmlEscape(path) + "</option>";
    c += "</select> <input size=\"40\" aria-label=\"values\" placeholder=\"values, comma-separated\"></div>\n";
  }
  const bool seeded = std::find(form.sweepable.begin(), form.sweepable.end(), "sample.seed") != form.sweepable.end();
  c += "<p>Mode <select id=\"sweep-mode\"><option>grid</option><option>zip</option></select></p>"
       "<h3>Replicates</h3><p>Runs per sweep point <input id=\"replicates\" size=\"4\" value=\"1\"> varying "
       "<input id=\"vary\" size=\"20\" value=\"" + std::string(seeded ? "sample.seed" : "") +
       "\"> <span class=\"hint\">(an integer field; each replicate adds 1)</span></p>"
       "<h3>Job</h3><p>Name <input id=\"job-name\" size=\"40\"> Token <input id=\"token\" type=\"password\" "
       "autocomplete=\"off\" size=\"24\"> <span class=\"hint\">(only if the server has one; kept for this "
       "browser session)</span></p><p><button id=\"submit\">Submit</button> <span class=\"error\" id=\"form-error\" "
       "role=\"alert\"></span></p></form>\n";
  std::string rows;
  inputRows(schema, "", rows);
  c += "<details><summary>The inputs as a table</summary><table><tr><th>Field (* required)</th><th>Type</th>"
       "<th>Unit</th><th>Description</th></tr>" + rows + "</table></details>";
  return page(id + ": " + process.value("title", ""), c, kSubmitScript);
}

}  // namespace rupture::server
