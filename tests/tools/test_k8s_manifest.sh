#!/usr/bin/env bash
# tools/k8s_indexed_job.yaml, as far as it can be checked without a Kubernetes cluster:
#  1. kubectl decodes it into a typed batch/v1 Job, offline (`kubectl set env --local`, which
#     needs no API server: `kubectl apply --dry-run=client` asks the server's API discovery even
#     with --validate=false), and no field is lost on the way, so a misspelled or mistyped field
#     fails; fields newer than this kubectl (an Indexed Job's, Kubernetes 1.21 and 1.28) are
#     named as not checked by it;
#  2. SHARDS, the pod's N, is the Job's completions;
#  3. the container's command, run here with the manifest's environment (the paths pointed at
#     this checkout and a test config, SEQMASSAGE_THREADS=1 where the kubelet would put the CPUs
#     requested) and JOB_COMPLETION_INDEX = 0 ... 3, runs tools/slurm_shards.sh, and merging its
#     shards gives every file of one unsharded run, byte for byte.
# What stays untested is a cluster running it (scheduling, the volume, retries per index).
#   bash tests/tools/test_k8s_manifest.sh     (tools/test.sh runs it after the Release build)
# Exit status: 0 passed; 1 failed; 3 skipped (no kubectl: tools/setup.sh installs Debian's
# kubernetes-client where kubectl is missing).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
manifest="$root/tools/k8s_indexed_job.yaml"
seqmassage="$root/build/src/cli/seqmassage"
work="$root/build/k8s-test"

log() { echo "test_k8s_manifest: $*"; }
fail() {
  echo "test_k8s_manifest: FAILED: $*" >&2
  exit 1
}
[ -x "$seqmassage" ] || fail "no $seqmassage: build first (cmake --build build)"
if ! command -v kubectl >/dev/null 2>&1; then
  log "SKIPPED: no kubectl (bash tools/setup.sh installs Debian's kubernetes-client)"
  exit 3
fi
python=/usr/bin/python3
[ -x "$python" ] || python=$(command -v python3) || fail "no python3 to read kubectl's JSON"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
# No cluster, and none of the user's: kubectl must not need one.
export KUBECONFIG=/dev/null

# --- 1. Decoded by kubectl, nothing lost -------------------------------------------------------
kubectl version --client -o json >client.json 2>/dev/null || fail "kubectl version --client failed"
# As written (kubectl's generic decoding keeps every field)...
kubectl annotate --local -f "$manifest" seqmassage-test=1 -o json >as-written.json 2>err.txt ||
  fail "kubectl cannot read $manifest: $(cat err.txt)"
# ... and as the typed batch/v1 Job (an unknown field is dropped, a mistyped one refused).
kubectl set env --local -f "$manifest" SEQMASSAGE_TEST=1 -o json >typed.json 2>err.txt ||
  fail "kubectl does not decode $manifest into a Job: $(cat err.txt)"
"$python" - "$manifest" <<'EOF' || exit 1
import json, re, sys

client = json.load(open("client.json"))["clientVersion"]
minor = int(re.match(r"\d+", client["minor"]).group())
version = f'{client["major"]}.{client["minor"]}'
written = json.load(open("as-written.json"))
typed = json.load(open("typed.json"))
written["metadata"].get("annotations", {}).pop("seqmassage-test", None)
if not written["metadata"].get("annotations"):
    written["metadata"].pop("annotations", None)
for c in typed["spec"]["template"]["spec"]["containers"]:
    c["env"] = [e for e in c.get("env", []) if e["name"] != "SEQMASSAGE_TEST"]
# Job fields newer than some kubectl versions, with the Kubernetes minor version adding them.
newer = {"spec.completionMode": 21, "spec.backoffLimitPerIndex": 28, "spec.maxFailedIndexes": 28}

def leaves(node, path=""):
    if isinstance(node, dict):
        for key, value in node.items():
            yield from leaves(value, f"{path}.{key}" if path else key)
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from leaves(value, f"{path}[{i}]")
    else:
        yield path, node

def lookup(node, path):
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", path):
        if part.startswith("["):
            i = int(part[1:-1])
            if not isinstance(node, list) or i >= len(node):
                return KeyError
            node = node[i]
        else:
            if not isinstance(node, dict) or part not in node:
                return KeyError
            node = node[part]
    return node

lost, unchecked = [], []
for path, value in leaves(written):
    got = lookup(typed, path)
    if got == value:
        continue
    since = next((v for p, v in newer.items() if path == p or path.startswith(p + ".")), None)
    if got is KeyError and since is not None and minor < since:
        unchecked.append(f"{path} (Kubernetes 1.{since})")
    else:
        lost.append(f"{path}: {json.dumps(value)} -> " +
                    ("dropped" if got is KeyError else json.dumps(got)))
if lost:
    sys.exit("test_k8s_manifest: FAILED: kubectl " + version + " does not keep these fields "
             "(misspelled or mistyped?):\n  " + "\n  ".join(lost))
spec = typed["spec"]
container = spec["template"]["spec"]["containers"][0]
env = {e["name"]: e.get("value") for e in container["env"]}
if env.get("SHARDS") != str(written["spec"]["completions"]):
    sys.exit(f"test_k8s_manifest: FAILED: SHARDS is {env.get('SHARDS')}, completions "
             f"{written['spec']['completions']}: N must be both")
print(f"test_k8s_manifest: kubectl {version} decodes {sys.argv[1].split('/')[-1]} into a "
      f"{typed['apiVersion']} {typed['kind']}, every field kept"
      + (f"; not known to this kubectl, so not checked by it: {', '.join(unchecked)}"
         if unchecked else ""))
# The container's command for step 3: argv and the environment, NUL-separated.
with open("command.bin", "wb") as f:
    for word in container["command"] + container["args"]:
        f.write(word.encode() + b"\0")
with open("env.bin", "wb") as f:
    for e in container["env"]:
        if "value" in e:
            f.write(f'{e["name"]}={e["value"]}'.encode() + b"\0")
EOF

# --- 3. The pods' command, run here ------------------------------------------------------------
mkdir -p job
cat >job/job.json <<'EOF'
{ "job": "sequence", "input": { "synthetic": { "frames": 60 } },
  "output": { "dir": "out", "timings": false } }
EOF
"$seqmassage" -q --threads 1 job/job.json
mv job/out reference
mapfile -d '' -t command <command.bin
mapfile -d '' -t manifest_env <env.bin
shards=4
for ((i = 0; i < shards; i++)); do
  # A pod's environment: the manifest's (then the test's paths over it) and nothing of ours.
  env -i PATH="$PATH" HOME="${HOME:-/root}" "${manifest_env[@]}" CHECKOUT="$root" \
    CONFIG="$work/job/job.json" SHARDS="$shards" SEQMASSAGE_THREADS=1 JOB_COMPLETION_INDEX="$i" \
    "${command[@]}" >"pod-$i.log" 2>&1 || fail "pod $i failed: $(tail -n5 "pod-$i.log")"
done
"$seqmassage" merge -q job/out || fail "the pods' shards do not merge"
diff -r -x '*.shard-*' reference job/out >diff.txt ||
  fail "the merged pods' output differs from one run: $(head -n5 diff.txt)"
log "the container's command as ${shards} pods (JOB_COMPLETION_INDEX 0-$((shards - 1))): merged, all" \
  "$(find job/out -type f ! -name '*.shard-*' | wc -l) files identical to one run"
log "passed (not tested: a Kubernetes cluster running it)"
