#!/usr/bin/python3
"""Checks api/openapi.yaml against the structure of OpenAPI 3.0 and the rules of Redocly's
"recommended" ruleset that apply to it (Redocly itself is not packaged for Debian, nor is
openapi-spec-validator in Debian 12, so the rules are implemented here on python3-yaml):

  spec structure     openapi 3.0.x, info.title/version, paths, responses with descriptions
  info-license(-url) license with name and url
  security-defined   every operation has security (its own or the document's), schemes declared
  operation-operationId, operation-operationId-unique, operation-operationId-url-safe
  operation-summary, operation-2xx-response, operation-4xx-response
  path-parameters-defined, operation-parameters-unique, no-path-trailing-slash
  no-unresolved-refs, no-unused-components, tag-description (operation tags are declared)
  no-server-example.com, no-identical-paths, no-enum-type-mismatch

    lint_openapi.py api/openapi.yaml      exit 0 when clean, 1 with one line per problem
"""
import re
import sys

import yaml

METHODS = {"get", "put", "post", "delete", "options", "head", "patch", "trace"}
problems = []


def report(where, rule, message):
    problems.append(f"{where}: {rule}: {message}")


def resolve(doc, ref, where):
    if not ref.startswith("#/"):
        report(where, "no-unresolved-refs", f"external $ref {ref!r} is not allowed here")
        return None
    node = doc
    for part in ref[2:].split("/"):
        part = part.replace("~1", "/").replace("~0", "~")
        if not isinstance(node, dict) or part not in node:
            report(where, "no-unresolved-refs", f"$ref {ref!r} does not resolve")
            return None
        node = node[part]
    return node


def walk_refs(doc, node, where, used):
    if isinstance(node, dict):
        ref = node.get("$ref")
        if isinstance(ref, str):
            if resolve(doc, ref, where) is not None and ref.startswith("#/components/"):
                if ref not in used:
                    used.add(ref)
                    walk_refs(doc, resolve(doc, ref, where), ref, used)
        for key, value in node.items():
            walk_refs(doc, value, where, used)
    elif isinstance(node, list):
        for value in node:
            walk_refs(doc, value, where, used)


def deref(doc, node, where):
    while isinstance(node, dict) and "$ref" in node:
        node = resolve(doc, node["$ref"], where)
    return node


def check_enums(node, where):
    if isinstance(node, dict):
        if isinstance(node.get("enum"), list) and isinstance(node.get("type"), str):
            kinds = {"string": str, "integer": int, "number": (int, float), "boolean": bool}
            kind = kinds.get(node["type"])
            for value in node["enum"]:
                if kind and not isinstance(value, kind):
                    report(where, "no-enum-type-mismatch", f"enum value {value!r} is not a {node['type']}")
        for value in node.values():
            check_enums(value, where)
    elif isinstance(node, list):
        for value in node:
            check_enums(value, where)


def main(path):
    with open(path, encoding="utf-8") as f:
        doc = yaml.safe_load(f)
    if not re.fullmatch(r"3\.0\.\d+", str(doc.get("openapi", ""))):
        report("openapi", "spec", "must be 3.0.x")
    info = doc.get("info") or {}
    for key in ("title", "version"):
        if not info.get(key):
            report("info", "spec", f"info.{key} is required")
    license_ = info.get("license") or {}
    if not license_.get("name"):
        report("info", "info-license", "info.license.name is required")
    if not license_.get("url"):
        report("info.license", "info-license-url", "info.license.url is required")
    for server in doc.get("servers", []):
        if "example.com" in server.get("url", ""):
            report("servers", "no-server-example.com", server["url"])
    schemes = (doc.get("components") or {}).get("securitySchemes") or {}
    declared_tags = {t["name"] for t in doc.get("tags", []) if t.get("description")}
    root_security = doc.get("security")
    operation_ids = {}
    templates = set()

    def check_security(requirements, where):
        if not isinstance(requirements, list) or not requirements:
            report(where, "security-defined", "no security requirement (use [{}] for an open operation)")
            return
        for requirement in requirements:
            for name in requirement or {}:
                if name not in schemes:
                    report(where, "security-defined", f"security scheme {name!r} is not declared")

    if root_security is not None:
        check_security(root_security, "security")
    for template, item in (doc.get("paths") or {}).items():
        if template != "/" and template.endswith("/"):
            report(template, "no-path-trailing-slash", "path ends with /")
        shape = re.sub(r"\{[^}]+\}", "{}", template)
        if shape in templates:
            report(template, "no-identical-paths", "another path has the same shape")
        templates.add(shape)
        names_in_path = re.findall(r"\{([^}]+)\}", template)
        path_params = [deref(doc, p, template) for p in item.get("parameters", [])]
        for method, op in item.items():
            if method not in METHODS:
                continue
            where = f"{method.upper()} {template}"
            op_id = op.get("operationId")
            if not op_id:
                report(where, "operation-operationId", "missing operationId")
            else:
                if op_id in operation_ids:
                    report(where, "operation-operationId-unique", f"{op_id!r} also on {operation_ids[op_id]}")
                operation_ids[op_id] = where
                if not re.fullmatch(r"[A-Za-z0-9\-._~]+", op_id):
                    report(where, "operation-operationId-url-safe", op_id)
            if not op.get("summary"):
                report(where, "operation-summary", "missing summary")
            for tag in op.get("tags", []):
                if tag not in declared_tags:
                    report(where, "tag-description", f"tag {tag!r} is not declared with a description")
            responses = op.get("responses") or {}
            codes = [str(c) for c in responses]
            if not any(c.startswith("2") for c in codes):
                report(where, "operation-2xx-response", "no 2xx response")
            if not any(c.startswith("4") for c in codes):
                report(where, "operation-4xx-response", "no 4xx response")
            for code, response in responses.items():
                response = deref(doc, response, where)
                if not isinstance(response, dict) or not response.get("description"):
                    report(where, "spec", f"response {code} needs a description")
            if "security" in op:
                check_security(op["security"], where)
            elif root_security is None:
                report(where, "security-defined", "no security on the operation nor on the document")
            params = path_params + [deref(doc, p, where) for p in op.get("parameters", [])]
            seen = set()
            for p in params:
                if not isinstance(p, dict):
                    continue
                key = (p.get("name"), p.get("in"))
                if key in seen and p in [deref(doc, q, where) for q in op.get("parameters", [])]:
                    report(where, "operation-parameters-unique", f"parameter {key} twice")
                seen.add(key)
                if p.get("in") == "path":
                    if not p.get("required"):
                        report(where, "spec", f"path parameter {p.get('name')!r} must be required")
                    if p.get("name") not in names_in_path:
                        report(where, "path-parameters-defined", f"{p.get('name')!r} is not in the path")
            declared = {p.get("name") for p in params if isinstance(p, dict) and p.get("in") == "path"}
            for name in names_in_path:
                if name not in declared:
                    report(where, "path-parameters-defined", f"path parameter {name!r} is not declared")
    used = set()
    walk_refs(doc, {k: v for k, v in doc.items() if k != "components"}, "document", used)
    for section, entries in (doc.get("components") or {}).items():
        if section == "securitySchemes":
            continue
        for name in entries or {}:
            if f"#/components/{section}/{name}" not in used:
                report(f"components/{section}/{name}", "no-unused-components", "never referenced")
    check_enums(doc, "document")
    for p in problems:
        print(p)
    print(f"{path}: {len(operation_ids)} operations, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "api/openapi.yaml"))
