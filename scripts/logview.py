"""Reading PETSc's -log_view table (shared by the benchmark scripts)."""
import re


def events(text):
    """-log_view events of a run's output: name -> (count, max time over the ranks), summed over the stages"""
    ev, inside = {}, False
    for l in text.splitlines():
        if l.startswith("Event ") and "Count" in l:
            inside = True
            continue
        if l.startswith("Memory usage") or l.startswith("Object Type"):
            inside = False
        f = l.split()
        if inside and len(f) >= 5 and re.match(r"^[A-Za-z_]\w*$", f[0]) and re.match(r"^\d+$", f[1]):
            try:
                c, t = int(f[1]), float(f[3])
            except ValueError:
                continue
            c0, t0 = ev.get(f[0], (0, 0.0))
            ev[f[0]] = (c0 + c, t0 + t)
    return ev
