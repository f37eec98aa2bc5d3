"""Checks the two CI examples of docs/ci.md: both YAML blocks parse (python3-yaml), and they do
what the page says:
- GitHub Actions: a job on an Ubuntu runner that checks out, runs sgapi-render with --junit FILE
  and --report DIR, publishes FILE with a JUnit test-report action and uploads DIR with
  actions/upload-artifact, both even when the run failed (if: always());
- GitLab CI: a job in a Debian or Ubuntu image whose script runs sgapi-render with --junit FILE
  and --report DIR, with artifacts:reports:junit FILE, DIR among artifacts:paths, and
  artifacts:when always;
- every sgapi-render option either uses is one `sgapi-render --help` lists.

    /usr/bin/python3 ci_examples.py docs/ci.md SGAPI_RENDER_BINARY
"""
import re
import shlex
import subprocess
import sys

import yaml


def fail(msg):
    sys.exit(f"FAIL: {msg}")


def render_options(command):
    """The --junit and --report values and every option of an sgapi-render command line."""
    words = shlex.split(command.replace("\\\n", " "))
    start = next(i for i, w in enumerate(words) if w.endswith("sgapi-render"))
    words = words[start + 1:]
    opts = [w for w in words if w.startswith("-")]
    value = lambda o: words[words.index(o) + 1] if o in words else None
    return value("--junit"), value("--report"), opts


def find_render(lines):
    for line in lines:
        if "sgapi-render " in line and "--compare" in line:
            return line
    fail("no sgapi-render --compare command")


def check_github(doc):
    jobs = doc.get("jobs") or fail("GitHub: no jobs")
    # PyYAML reads the key `on` as the boolean true (YAML 1.1).
    if "on" not in doc and True not in doc:
        fail("GitHub: no `on` trigger")
    (name, job), = jobs.items()
    if "ubuntu" not in str(job.get("runs-on", "")):
        fail(f"GitHub: job {name} does not run on an Ubuntu runner")
    steps = job.get("steps") or fail("GitHub: no steps")
    uses = [s.get("uses", "") for s in steps]
    if not any(u.startswith("actions/checkout@") for u in uses):
        fail("GitHub: no checkout step")
    junit, report, opts = render_options(find_render(s.get("run", "") for s in steps))
    if not junit or not report:
        fail("GitHub: sgapi-render without --junit FILE and --report DIR")
    publish = [s for s in steps if "junit" in s.get("uses", "").lower()
               or "test-reporter" in s.get("uses", "")]
    if not publish:
        fail("GitHub: no step publishes the JUnit file")
    paths = str(publish[0].get("with", {}).get("report_paths")
                or publish[0].get("with", {}).get("path"))
    if paths != junit:
        fail(f"GitHub: the JUnit step reads {paths}, sgapi-render writes {junit}")
    upload = [s for s in steps if s.get("uses", "").startswith("actions/upload-artifact@")]
    if not upload or upload[0].get("with", {}).get("path") != report:
        fail(f"GitHub: no upload-artifact step of the report folder {report}")
    for step in publish[:1] + upload[:1]:
        if step.get("if") != "always()":
            fail(f"GitHub: step {step.get('name')} does not run when the comparison fails")
    return opts


def check_gitlab(doc):
    jobs = {k: v for k, v in doc.items() if isinstance(v, dict) and "script" in v}
    if len(jobs) != 1:
        fail(f"GitLab: {len(jobs)} jobs, expected one")
    (name, job), = jobs.items()
    if not re.match(r"(debian|ubuntu):", str(job.get("image", ""))):
        fail(f"GitLab: job {name} does not run in a Debian or Ubuntu image")
    junit, report, opts = render_options(find_render(job["script"]))
    if not junit or not report:
        fail("GitLab: sgapi-render without --junit FILE and --report DIR")
    art = job.get("artifacts") or fail("GitLab: no artifacts")
    if art.get("reports", {}).get("junit") != junit:
        fail(f"GitLab: artifacts:reports:junit is not {junit}")
    if not any(p.rstrip("/") == report.rstrip("/") for p in art.get("paths", [])):
        fail(f"GitLab: the report folder {report} is not among the artifacts' paths")
    if art.get("when") != "always":
        fail("GitLab: artifacts are not kept when the comparison fails (when: always)")
    return opts


def main():
    page, render = sys.argv[1], sys.argv[2]
    text = open(page, encoding="utf-8").read()
    blocks = re.findall(r"^```yaml\n(.*?)^```", text, re.S | re.M)
    if len(blocks) != 2:
        fail(f"{page}: {len(blocks)} yaml blocks, expected 2 (GitHub Actions, GitLab CI)")
    docs = []
    for i, block in enumerate(blocks):
        try:
            docs.append(yaml.safe_load(block))
        except yaml.YAMLError as e:
            fail(f"{page}: yaml block {i + 1} does not parse: {e}")
    opts = check_github(docs[0]) + check_gitlab(docs[1])
    help_text = subprocess.run([render, "--help"], capture_output=True, text=True,
                               check=True).stdout
    for o in opts:
        if not re.search(r"(^|[\s,])" + re.escape(o) + r"\b", help_text):
            fail(f"sgapi-render has no option {o}")
    print(f"ci_examples: both YAML blocks check out ({len(set(opts))} sgapi-render options)")


if __name__ == "__main__":
    main()
