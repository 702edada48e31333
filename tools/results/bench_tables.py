#!/usr/bin/python3
"""Markdown tables from a `sixway bench --report` JSON file, printed to stdout.

Usage: python3 tools/results/bench_tables.py REPORT.json

Every time is the median of the report's timed runs with the min-max range after it, in milliseconds of GPU
timestamps; the sections present in the report become tables (simulation, lightmap stages, end-to-end frame,
network). docs/benchmarks.md shows the output of one run.
"""
import json
import sys


def ms(value):
    """A time in ms with about three significant digits."""
    if value >= 100:
        return f"{value:.0f}"
    if value >= 10:
        return f"{value:.1f}"
    return f"{value:.2f}"


def timing(t, bold=False):
    median = f"**{ms(t['median_ms'])}**" if bold else ms(t["median_ms"])
    if len(t["samples_ms"]) == 1:
        return median
    return f"{median} ({ms(t['min_ms'])}–{ms(t['max_ms'])})"


def stage_map(entry):
    return {s["name"]: s for s in entry["stages"]}


def load_average(value):
    return "unknown" if value is None else " / ".join(f"{v:.2f}" for v in value)


def machine(report):
    m = report["machine"]
    lines = [
        f"- device: {report['device']} ({report['driver']}), Vulkan {report['vulkan']}",
        f"- CPU: {m['cpu']}, {m['logical_cores']} logical cores; load average (1 / 5 / 15 min) "
        f"{load_average(report['load_average_start'])} at the start, {load_average(report['load_average_end'])} "
        "at the end",
        f"- {report['date_utc']}, {report['seconds']:.0f} s in all; {report['warmup']} warm-up runs, then "
        f"{report['repeats']} timed runs ({report['repeats_large']} timed runs and at most one warm-up run for "
        f"lattices over 2 M cells; a simulation run is {report['sim_steps']} steps); times in ms, median (min–max)",
        f"- scene: `{report['scene'].split('/')[-1]}`",
    ]
    return "\n".join(lines)


def simulation(section):
    stages = []
    for lattice in section["lattices"]:
        for s in lattice["stages"]:
            if s["name"] not in stages:
                stages.append(s["name"])
    rows = [
        "| lattice | cells | " + " | ".join(stages) + " | **step** | MLUPs | watchdog (per submission) | runs |",
        "|---" * (len(stages) + 6) + "|",
    ]
    for lattice in section["lattices"]:
        by_name = stage_map(lattice)
        size = "x".join(str(n) for n in lattice["size"])
        cells = f"{lattice['cells'] / 1e6:.2f} M"
        times = [timing(by_name[n]) if n in by_name else "—" for n in stages]
        mlups = lattice["mlups"]
        rate = f"{mlups['median']:.2f} ({mlups['min']:.2f}–{mlups['max']:.2f})"
        rows.append(f"| {size} | {cells} | " + " | ".join(times) +
                    f" | {timing(lattice['total'], True)} | {rate} | {timing(lattice['watchdog'])} | {lattice['runs']} |")
    return "\n".join(rows)


def lightmaps(section):
    sizes = section["sizes"]
    stages = []
    for entry in sizes:
        for s in entry["stages"]:
            if s["name"] not in stages:
                stages.append(s["name"])
    header = "| stage | " + " | ".join(f"{e['size']}²" for e in sizes) + " |"
    rows = [header, "|---" * (len(sizes) + 1) + "|"]
    for name in stages:
        cells = []
        for entry in sizes:
            s = stage_map(entry).get(name)
            cells.append(timing(s) if s else "—")
        in_total = all(stage_map(e).get(name, {"in_total": True})["in_total"] for e in sizes)
        label = name if in_total else f"{name} (instead of fp32; not in the total)" if name == "network fp16" \
            else f"{name} (not in the total)"
        rows.append(f"| {label} | " + " | ".join(cells) + " |")
    rows.append("| **real-time total** | " + " | ".join(timing(e["total"], True) for e in sizes) + " |")
    if all("neural_over_baker" in e for e in sizes):
        rows.append("| neural lightmaps / exact baker (medians) | " +
                    " | ".join(f"{e['neural_over_baker']:.2f}x" for e in sizes) + " |")
    frame = "x".join(str(n) for n in section["frame"])
    lattice = "x".join(str(n) for n in section["lattice"])
    note = (f"Frame {frame}, the bench plume on a {lattice} grid, {section['lights']} lights, "
            f"{section['obstacles']} obstacle(s), network `{section['weights'].split('/')[-1]}`.")
    return note + "\n\n" + "\n".join(rows)


def frame(section):
    rows = ["| stage | median | min | max |", "|---|---|---|---|"]
    for s in section["stages"]:
        rows.append(f"| {s['name']} | {ms(s['median_ms'])} | {ms(s['min_ms'])} | {ms(s['max_ms'])} |")
    for label, key in (("simulation (sum)", "simulation"), ("real-time rendering (sum)", "rendering")):
        t = section[key]
        rows.append(f"| {label} | {ms(t['median_ms'])} | {ms(t['min_ms'])} | {ms(t['max_ms'])} |")
    t = section["total"]
    rows.append(f"| **whole frame (GPU)** | **{ms(t['median_ms'])}** | {ms(t['min_ms'])} | {ms(t['max_ms'])} |")
    t = section["wall"]
    rows.append(f"| wall clock (host waits and the frame's readback included) | {ms(t['median_ms'])} | "
                f"{ms(t['min_ms'])} | {ms(t['max_ms'])} |")
    lattice = "x".join(str(n) for n in section["lattice"])
    size = section["lightmap_size"]
    frame_size = "x".join(str(n) for n in section["frame"])
    note = (f"One frame: {section['steps_per_frame']} lattice steps of {lattice}, then {size}x{size} lightmaps "
            f"({section['precision']} feature maps, `{section['weights'].split('/')[-1]}`) and a {frame_size} frame; "
            f"{section['runs']} frames timed after {section['warmup']} warm-up frames.")
    return note + "\n\n" + "\n".join(rows)


def network(section):
    rows = ["| size | as one stage, ms | sum of the layer stages, ms | GFLOP | GFLOP/s (one stage) | process CPU ms |",
            "|---|---|---|---|---|---|"]
    for entry in section["sizes"]:
        whole = entry["whole"]
        rows.append(f"| {entry['size']}² | {timing(whole)} | {timing(entry['total'])} | {entry['flops'] / 1e9:.2f} | "
                    f"{entry['flops'] / whole['median_ms'] * 1e-6:.1f} | {ms(entry['process_cpu_ms'])} |")
    note = (f"`{section['weights'].split('/')[-1]}`, {section['precision']} feature maps: the whole network as one "
            "timed stage, and the same network with a timed stage per layer (the sum of the stages); process CPU "
            "time is of the per-layer submissions (all of lavapipe's threads).")
    return note + "\n\n" + "\n".join(rows)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bench_tables.py REPORT.json")
    path = sys.argv[1]
    try:
        with open(path) as f:
            report = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"bench_tables.py: {path}: {e}")
    try:
        parts = [machine(report)]
        titles = {"sim": "### Simulation: one lattice step",
                  "lightmaps": "### Lightmap stages",
                  "frame": "### End-to-end frame",
                  "network": "### Network alone"}
        makers = {"sim": simulation, "lightmaps": lightmaps, "frame": frame, "network": network}
        for key in ("sim", "lightmaps", "frame", "network"):
            if key in report:
                parts.append(titles[key] + "\n\n" + makers[key](report[key]))
    except (KeyError, TypeError, IndexError) as e:
        sys.exit(f"bench_tables.py: {path}: not a sixway bench report (missing {e})")
    print("\n\n".join(parts))


if __name__ == "__main__":
    main()
