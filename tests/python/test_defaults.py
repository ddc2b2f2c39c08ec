# One default per option (issue 37): every function's keyword argument that a front end
# shares defaults to the library's (meshsal.defaults(), meshsal::Request), and the command
# line's --help shows the same.
import inspect
import re

import meshsal


def test_every_function_takes_the_librarys_defaults():
    d = meshsal.defaults()
    checked = 0
    for name in dir(meshsal):
        f = getattr(meshsal, name)
        if not callable(f) or name.startswith("_") or isinstance(f, type):
            continue
        try:
            params = inspect.signature(f).parameters
        except (TypeError, ValueError):
            continue
        for key, p in params.items():
            if key in d and p.default is not inspect.Parameter.empty and p.default is not None:
                assert p.default == d[key], f"{name}({key}={p.default!r}): the library's default is {d[key]!r}"
                checked += 1
    assert checked >= 20


def test_the_command_line_shows_the_same_defaults(cli):
    d = meshsal.defaults()
    flags = {"--method": d["method"], "--model": d["model"], "--precision": d["precision"], "--backend": d["backend"],
             "--eps-frac": d["eps_frac"], "--scales": ",".join(f"{s:g}" for s in d["scales"]),
             "--weights": d["weights"], "--weight-floor": d["weight_floor"], "--restarts": d["restarts"],
             "--seed": d["seed"], "--resolution": d["resolution"], "--depth-tol": d["depth_tol"], "--size": d["size"],
             "--max-faces": d["max_faces"], "--threads": d["threads"]}
    seen = 0
    for command in ("saliency", "simplify", "view", "render", "viewpoint", "batch", "compare", "demo"):
        text = cli(command, "--help").stdout
        for flag, value in flags.items():
            # CLI11 shows "  --flag TYPE[:check]=DEFAULT   help".
            m = re.search(r"^\s+" + re.escape(flag) + r" \S*?=(\S+)", text, re.M)
            if m:
                shown = m.group(1)
                assert shown == str(value) or (isinstance(value, float) and float(shown) == value), \
                    f"meshsal {command} {flag}: shows {shown}, the library's default is {value}"
                seen += 1
    assert seen >= 30
