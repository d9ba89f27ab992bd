#!/usr/bin/env python3
"""Reads a deployment manifest (deploy/hosts/*.yaml) and prints, for deploy/deploy.sh, the shell
command each host runs for start, stop or status, one line per host and phase:
HOST<TAB>SSH_TARGET<TAB>COMMAND. Start goes in phases (recorder, planners, simulator, goal) so
that every listener is up before the inputs flow; stop goes the other way.

    manifest.py MANIFEST start|stop|status [--host NAME]
"""
import os
import shlex
import sys

import yaml

SERVICES = ["logger", "mapping", "awareness", "fpm", "som", "eam", "arbiter", "sim", "goal"]
PHASES = [["logger"], ["mapping", "awareness", "fpm", "som", "eam", "arbiter"], ["sim"], ["goal"]]
GLOBAL_KEYS = {"name", "prefix", "lcm_url", "config", "root", "run_dir", "bin_dir", "respawn",
               "hosts"}
HOST_KEYS = {"ssh", "prefix", "lcm_url", "config", "root", "run_dir", "bin_dir", "respawn",
             "services"}


class ManifestError(Exception):
    pass


def service_entries(host, entries):
    """[(name, args string)] from a list of names or one-key mappings name: args."""
    if not isinstance(entries, list) or not entries:
        raise ManifestError(f"host {host}: 'services' must be a non-empty list")
    out = []
    for entry in entries:
        if isinstance(entry, str):
            name, args = entry, ""
        elif isinstance(entry, dict) and len(entry) == 1:
            name, args = next(iter(entry.items()))
            args = "" if args is None else str(args)
        else:
            raise ManifestError(f"host {host}: a service is a name or 'name: arguments', "
                                f"not {entry!r}")
        if name not in SERVICES:
            raise ManifestError(f"host {host}: unknown service {name!r} "
                                f"(known: {', '.join(SERVICES)})")
        if name in (n for n, _ in out):
            raise ManifestError(f"host {host}: service {name} listed twice")
        out.append((name, args))
    return out


def load(path, default_root):
    try:
        with open(path) as f:
            doc = yaml.safe_load(f)
    except OSError as e:
        raise ManifestError(f"cannot read {path}: {e.strerror}")
    except yaml.YAMLError as e:
        raise ManifestError(f"{path} is not valid YAML: {e}")
    if not isinstance(doc, dict) or not isinstance(doc.get("hosts"), dict) or not doc["hosts"]:
        raise ManifestError(f"{path}: needs a 'hosts' mapping (name: {{ssh, services}})")
    unknown = set(doc) - GLOBAL_KEYS
    if unknown:
        raise ManifestError(f"{path}: unknown key(s) {', '.join(sorted(unknown))}")
    hosts = []
    for name, spec in doc["hosts"].items():
        spec = spec or {}
        if not isinstance(spec, dict):
            raise ManifestError(f"host {name}: expected a mapping")
        unknown = set(spec) - HOST_KEYS
        if unknown:
            raise ManifestError(f"host {name}: unknown key(s) {', '.join(sorted(unknown))}")

        def get(key, default=None):
            value = spec.get(key, doc.get(key, default))
            return default if value is None else value

        root = str(get("root", default_root))
        hosts.append({
            "name": str(name),
            "ssh": str(get("ssh", "local")),
            "prefix": str(get("prefix", "")),
            "lcm_url": str(get("lcm_url", "")),
            "root": root,
            "config": os.path.join(root, str(get("config", "deploy/config/default.yaml"))),
            "run_dir": os.path.join(root, str(get("run_dir", "run"))),
            "bin_dir": os.path.join(root, str(get("bin_dir", "build/bin"))),
            "respawn": bool(get("respawn", False)),
            "services": service_entries(name, spec.get("services")),
        })
    return hosts


def service_command(host, name, args, action):
    cmd = [f"deploy/launch/{name}.sh", action, "--prefix", host["prefix"], "--config",
           host["config"], "--run-dir", host["run_dir"], "--bin-dir", host["bin_dir"]]
    if host["lcm_url"]:
        cmd += ["--lcm-url", host["lcm_url"]]
    if action == "start":
        if host["respawn"]:
            cmd.append("--respawn")
        if args:
            cmd += ["--"] + shlex.split(args)
    return " ".join(shlex.quote(c) for c in cmd)


def host_command(host, names, action):
    """POSIX sh: every service's action, exit code 1 (3 for status) if any of them failed."""
    failed = "3" if action == "status" else "1"
    parts = [f"cd {shlex.quote(host['root'])} || exit 1", "rc=0"]
    services = dict(host["services"])
    for name in names:
        parts.append(f"{service_command(host, name, services[name], action)} || rc={failed}")
    parts.append("exit $rc")
    return "; ".join(parts)


def plan(hosts, action):
    if action == "status":
        phases = [SERVICES]
    elif action == "start":
        phases = PHASES
    else:
        phases = list(reversed(PHASES))
    lines = []
    for phase in phases:
        for host in hosts:
            names = [n for n in (reversed(phase) if action == "stop" else phase)
                     if n in dict(host["services"])]
            if names:
                lines.append((host["name"], host["ssh"], host_command(host, names, action)))
    return lines


def main(argv):
    args = argv[1:]
    only = None
    if "--host" in args:
        i = args.index("--host")
        if i + 1 >= len(args):
            raise ManifestError("--host needs a host name")
        only = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2 or args[1] not in ("start", "stop", "status"):
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    default_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    hosts = load(args[0], default_root)
    if only is not None:
        hosts = [h for h in hosts if h["name"] == only]
        if not hosts:
            raise ManifestError(f"no host {only} in {args[0]}")
    for name, ssh, command in plan(hosts, args[1]):
        print(f"{name}\t{ssh}\t{command}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except ManifestError as e:
        print(f"manifest: {e}", file=sys.stderr)
        sys.exit(2)
