#!/usr/bin/env bash
# Load check of `netspec serve` on loopback: 50 concurrent page and API requests, 8 solves queued
# at once (2 running, 6 waiting), then 10 runs kept; prints failures, times and the server's
# memory. Usage: scripts/serve-load.sh [path/to/netspec]
set -euo pipefail
netspec=${1:-${CARGO_TARGET_DIR:-$HOME/.cache/netspec/target}/release/netspec}
root=$(mktemp -d)
port=$((20000 + RANDOM % 20000))
base=http://127.0.0.1:$port
cat > "$root/small.toml" <<'EOF'
name = "small"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [6, 18]
[coverage]
range = 2
[features]
dead_ends = "allow"
[weights]
length = 1
distance = 1
[solver]
name = "highs"
time_limit = 30
threads = 1
EOF
"$netspec" serve --root "$root" --port "$port" --max-solves 2 --threads 2 >/dev/null &
pid=$!
trap 'kill $pid; rm -rf "$root"' EXIT
for _ in $(seq 50); do curl -sf "$base/api/specs" >/dev/null && break; sleep 0.1; done
rss() { awk '/VmRSS/ {print $2 / 1024 " MiB"}' "/proc/$pid/status"; }
echo "memory at start: $(rss)"

# 50 concurrent requests: the page, its script, the list, a thumbnail, a spec.
urls=(/ /assets/app.js /api/specs "/api/thumb?example=fig2b" "/api/spec?example=fig2e")
t0=$(date +%s.%N)
fails=$(for i in $(seq 0 49); do echo "$base${urls[$((i % 5))]}"; done |
  xargs -P 50 -n 1 curl -s -o /dev/null -w '%{http_code}\n' | grep -vc '^200$' || true)
t1=$(date +%s.%N)
echo "50 concurrent page and API requests: $fails failed, $(echo "$t1 - $t0" | bc) s"

# 8 solves queued at once, each followed to its end.
spec=$(curl -sf "$base/api/spec?path=small.toml" | python3 -c 'import json,sys; print(json.dumps({"spec": json.load(sys.stdin)["spec"]}))')
t0=$(date +%s.%N)
ids=$( (for _ in $(seq 8); do curl -sf -w '\n' -H 'content-type: application/json' -d "$spec" "$base/api/solve" & done; wait) | grep -o 'r[0-9]\{4\}')
wait_done() { until curl -sf "$base/api/runs/$1" | grep -q '"state":"finished"'; do sleep 0.1; done; }
for id in $ids; do wait_done "$id"; done
t1=$(date +%s.%N)
valid=$(curl -sf "$base/api/runs" | python3 -c 'import json,sys; print(sum(r["summary"]["verdict"] == "valid" for r in json.load(sys.stdin)["runs"]))')
echo "8 queued solves: $valid of 8 finished valid, $(echo "$t1 - $t0" | bc) s"

# Ten runs kept: two more.
for _ in 1 2; do id=$(curl -sf -H 'content-type: application/json' -d "$spec" "$base/api/solve" | python3 -c 'import json,sys; print(json.load(sys.stdin)["id"])'); wait_done "$id"; done
echo "memory with $(curl -sf "$base/api/runs" | python3 -c 'import json,sys; print(len(json.load(sys.stdin)["runs"]))') runs kept: $(rss)"

# Time from Solve to the first design drawn, on the 12 x 12 Fig. 2b.
fig=$(curl -sf "$base/api/spec?example=fig2b" | python3 -c 'import json,sys; s=json.load(sys.stdin)["spec"]; s["solver"]={"name":"highs","time_limit":60,"threads":1}; print(json.dumps({"spec": s}))')
id=$(curl -sf -H 'content-type: application/json' -d "$fig" "$base/api/solve" | python3 -c 'import json,sys; print(json.load(sys.stdin)["id"])')
curl -sN "$base/api/runs/$id/events" | python3 -c '
import json, sys
for line in sys.stdin:
    if line.startswith("data:"):
        e = json.loads(line[5:])
        if e["kind"] == "design":
            print("fig2b: first design %.2f s after Solve (objective %.4f)" % (e["t"], e["objective"]))
            break
'
curl -sf -X POST "$base/api/runs/$id/stop" >/dev/null
