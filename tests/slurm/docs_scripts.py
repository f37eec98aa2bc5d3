"""docs/scale-out.md against the files it shows: each batch script of tools/slurm/ is in the page
whole, byte for byte, as a ```sh block (the page's copy and the tested copy are one); the scripts
parse (sh -n); the Kubernetes indexed Job parses as YAML and its shard count is its completions.

    docs_scripts.py SOURCE_DIR
"""
import pathlib
import re
import subprocess
import sys

import yaml


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


src = pathlib.Path(sys.argv[1])
page = (src / "docs/scale-out.md").read_text()
blocks = re.findall(r"^```sh\n(.*?^)```$", page, re.S | re.M)
scripts = sorted((src / "tools/slurm").glob("*.sbatch"))
if len(scripts) < 2:
    fail(f"tools/slurm has {len(scripts)} batch scripts")
for script in scripts:
    text = script.read_text()
    if text not in blocks:
        fail(f"docs/scale-out.md does not show {script.name} as it is (a ```sh block equal to "
             f"the file)")
    r = subprocess.run(["sh", "-n", str(script)], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{script.name} does not parse: {r.stderr}")
    print(f"{script.name}: in the page byte for byte, parses")
# The page submits the files by their paths.
for name in ("tools/slurm/render-turntable.sbatch", "tools/slurm/assemble-turntable.sbatch"):
    if not any(f"sbatch" in b and name in b for b in blocks):
        fail(f"no command of the page submits {name}")

manifests = re.findall(r"^```yaml\n(.*?)^```$", page, re.S | re.M)
if len(manifests) != 1:
    fail(f"{len(manifests)} yaml blocks, expected the indexed Job")
job = yaml.safe_load(manifests[0])
spec = job["spec"]
if job["kind"] != "Job" or spec["completionMode"] != "Indexed":
    fail("the manifest is not an indexed Job")
args = " ".join(spec["template"]["spec"]["containers"][0]["args"])
m = re.search(r'--shard "\$JOB_COMPLETION_INDEX/(\d+)"', args)
if not m or int(m.group(1)) != spec["completions"]:
    fail(f"the Job's shard count is not its completions ({spec['completions']}): {args}")
print(f"Kubernetes indexed Job: parses, {spec['completions']} shards = completions")
