"""Run a variant of a scene through `amphora run` for a study: the scene file with some keys
replaced (`key = value` lines, first match), its output in its own directory and no field
output beyond the first and last step. A run that amphora stops as diverged/unstable (exit 3)
is a result, not an error: its step and time are parsed from the message."""
import os
import re
import subprocess

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
amphora = os.environ.get("AMPHORA", os.path.join(here, "build", "release", "apps", "amphora"))


def run_variant(scene_name, out_dir, values, threads=1):
    """Returns (result, out_dir) with result = {"stable", "stdout", and blowup_step/blowup_time
    if exit 3}; raises on any other failure. `values` maps keys to replacement text."""
    text = open(os.path.join(here, "scenes", scene_name)).read()
    values = dict(values, output_dir=f'"{out_dir}"', output_every="100000")
    for key, value in values.items():
        text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, count=1, flags=re.M)
        if n != 1:
            raise KeyError(f"{scene_name} has no line '{key} = ...'")
    scene = out_dir + ".toml"
    open(scene, "w").write(text)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="false")
    p = subprocess.run([amphora, "run", scene], capture_output=True, text=True, env=env)
    if p.returncode not in (0, 3):
        raise RuntimeError(f"{scene}: exit {p.returncode}\n{p.stderr}")
    result = {"stable": int(p.returncode == 0), "stdout": p.stdout}
    if p.returncode == 3:
        m = re.search(r"at step (\d+), t = ([0-9.e+-]+)", p.stderr)
        result.update(blowup_step=int(m.group(1)), blowup_time=float(m.group(2)))
    return result
