#!/usr/bin/env python3
"""Syntax and consistency checks of the deploy/ files this machine cannot run (no container engine,
no systemd): the compose file parses as YAML and publishes on loopback, the Dockerfile's
instructions and stages are well formed and it runs as a non-root user with a health check, the
systemd unit parses with its hardening options, and every RUPTURE_* variable in the examples is one
that rupture-server --help lists. Exit status 0 when all hold; each failure is printed.

usage: check_deploy_files.py REPO_ROOT RUPTURE_SERVER_BINARY
"""
import configparser
import re
import shutil
import subprocess
import sys
from pathlib import Path

import yaml

root, server = Path(sys.argv[1]), sys.argv[2]
deploy = root / "deploy"
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


help_text = subprocess.run([server, "--help"], capture_output=True, text=True, check=True).stdout
known_variables = set(re.findall(r"env (RUPTURE_[A-Z_]+)", help_text))
check(len(known_variables) > 10, "rupture-server --help lists its variables")

# compose.yaml
compose = yaml.safe_load((deploy / "compose.yaml").read_text())
service = compose.get("services", {}).get("rupture", {})
check(service.get("build", {}).get("dockerfile") == "deploy/Dockerfile", "compose builds deploy/Dockerfile")
check((deploy / service.get("build", {}).get("context", "..")).resolve() == root.resolve(), "compose context is the repository")
check(all(str(p).startswith("127.0.0.1:") for p in service.get("ports", [])), "compose publishes on loopback only")
check(any(str(v).endswith(":/data") for v in service.get("volumes", [])), "compose keeps /data in a volume")
check("healthcheck" in service, "compose has a health check")
for name in service.get("environment", {}):
    check(name in known_variables, f"compose sets {name}, which rupture-server knows")

# Dockerfile
instructions = {"FROM", "RUN", "CMD", "LABEL", "EXPOSE", "ENV", "ADD", "COPY", "ENTRYPOINT", "VOLUME", "USER",
                "WORKDIR", "ARG", "ONBUILD", "STOPSIGNAL", "HEALTHCHECK", "SHELL"}
lines, current = [], ""
for raw in (deploy / "Dockerfile").read_text().splitlines():
    if not current and (not raw.strip() or raw.lstrip().startswith("#")):
        continue
    current += raw.rstrip("\\").strip() + " "
    if not raw.rstrip().endswith("\\"):
        lines.append(current.strip())
        current = ""
check(current == "", "Dockerfile ends without a dangling continuation")
stages, last_user = [], None
for line in lines:
    keyword = line.split()[0].upper()
    check(keyword in instructions, f"Dockerfile instruction {keyword!r} is known")
    if keyword == "FROM":
        parts = line.split()
        stages.append(parts[3] if len(parts) >= 4 and parts[2].upper() == "AS" else None)
        last_user = None
    if keyword == "USER":
        last_user = line.split()[1]
    if keyword == "COPY" and "--from=" in line:
        check(re.search(r"--from=(\S+)", line).group(1) in stages[:-1], "COPY --from names an earlier stage")
    if keyword == "ENV":
        for name in re.findall(r"(RUPTURE_[A-Z_]+)=", line):
            check(name in known_variables, f"Dockerfile sets {name}, which rupture-server knows")
check(len(stages) >= 2, "Dockerfile builds in one stage and runs in another")
check(last_user not in (None, "root", "0"), "the image runs as a non-root user")
check(any(l.upper().startswith("HEALTHCHECK") for l in lines), "the image has a HEALTHCHECK")
check(any(l.upper().startswith("VOLUME") for l in lines), "the image declares its data volume")

# systemd unit
unit = configparser.ConfigParser(strict=False, interpolation=None)
unit.optionxform = str
unit.read(deploy / "rupture-server.service")
check(set(unit.sections()) == {"Unit", "Service", "Install"}, "the unit has [Unit], [Service] and [Install]")
service_section = unit["Service"] if unit.has_section("Service") else {}
check(service_section.get("ExecStart", "").startswith("/"), "ExecStart is an absolute path")
check(service_section.get("User") not in (None, "root"), "the service runs as its own user")
for option in ("NoNewPrivileges", "ProtectSystem", "ProtectHome", "PrivateTmp", "RestrictAddressFamilies",
               "SystemCallFilter", "CapabilityBoundingSet", "StateDirectory"):
    check(option in service_section, f"the unit sets {option}")
if shutil.which("systemd-analyze"):
    verify = subprocess.run(["systemd-analyze", "verify", str(deploy / "rupture-server.service")],
                            capture_output=True, text=True)
    # The binary is not installed here; any other complaint is a real one.
    complaints = [l for l in verify.stderr.splitlines() if l.strip() and "rupture-server" not in l.split(":")[-1]
                  and "not executable" not in l and "No such file" not in l]
    check(not complaints, "systemd-analyze verify: " + "; ".join(complaints))

# The Slurm site example (an EnvironmentFile)
text = (deploy / "slurm" / "site-example.env").read_text()
for name in re.findall(r"^#?\s*(RUPTURE_[A-Z_]+)=", text, flags=re.M):
    check(name in known_variables, f"site-example.env sets {name}, which rupture-server knows")

for f in failures:
    print("FAIL:", f)
print(f"deploy files: {len(failures)} failed")
sys.exit(1 if failures else 0)
