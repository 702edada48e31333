#!/usr/bin/python3
"""docs/results.md from the `sixway eval --scene` reports that tools/results.sh writes, printed to stdout.

Usage: eval_tables.py REPORT_DIR MACHINE.json [BENCH_TABLES.md]

REPORT_DIR holds the reports by the names results.sh gives them (multiple.json, single.json, orbit.json,
density_0.5.json, density_2.json, shadows_on.json, shadows_off.json); MACHINE.json describes the machine and the
run (results.sh writes it). Every number printed comes from those files. When REPORT_DIR/gallery/ holds the
per-scene reports of tools/results/gallery.sh, the page opens with that gallery.
"""
import json
import math
import os
import sys

METHODS = ["neural", "reference", "reference-ms", "traditional", "traditional-ms", "guide-lit"]


def load(directory, name):
    with open(os.path.join(directory, name + ".json")) as f:
        return json.load(f)


def db(v):
    return "–" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.2f}"


def ms(v):
    if v is None:
        return "–"
    return f"{v:.0f}" if v >= 100 else f"{v:.1f}" if v >= 10 else f"{v:.2f}"


def sci(v):
    return "–" if v is None else f"{v:.2e}"


GALLERY_METHODS = ["neural", "reference", "traditional-ms", "reference-ms"]


def gallery_section(directory):
    """One strip and one row of masked PSNRs per shipped scene (tools/results/gallery.sh); "" without them."""
    root = os.path.join(directory, "gallery")
    scenes = sorted(d for d in os.listdir(root) if os.path.isfile(os.path.join(root, d, "report.json"))) \
        if os.path.isdir(root) else []
    if not scenes:
        return ""
    reports = {name: load(os.path.join(root, name), "report") for name in scenes}
    first = reports[scenes[0]]
    size = f"{first['size'][0]}×{first['size'][1]}"
    rows = ["| scene | scene frame | " + " | ".join(GALLERY_METHODS) + " | traditional-ms at 0° |",
            "|---|---|" + "---|" * (len(GALLERY_METHODS) + 1)]
    for name in scenes:
        report = reports[name]
        frame = report["strip"]["frame"]
        image = report["per_frame"][frame]["image"]
        rows.append(f"| {name} | {report.get('warmup_frames', 0) + frame} | " +
                    " | ".join(db(image[m]["psnr_masked_db"]) for m in GALLERY_METHODS) +
                    f" | {db(report['per_frame'][0]['image']['traditional-ms']['psnr_masked_db'])} |")
    strips = "\n\n".join(f"**{name}**\n\n![{name}](results/gallery_{name}.png)" for name in scenes)
    return f"""## Every shipped scene

Each shipped scene (`assets/scenes/`) at {size} with {first['lightmap_size']}² lightmaps after its warm-up, the
camera orbiting {first['camera_orbit_deg_per_frame']:g}° a frame, against the path tracer with every scattering
order ({first['pathtrace_spp']} spp). Each strip is the last frame, seen {2 * first['camera_orbit_deg_per_frame']:g}°
from where the flipbook was baked; left to right the **truth**, **neural** (the shipped all-orders network),
**reference** (the exact single-scattering baker), **traditional-ms** (a flipbook baked with multiple scattering
from the first frame's view, as games ship it), then |method − truth| × 4 for the three (false colour, black = 0,
white ≥ 0.25). Made by `tools/results/gallery.sh`. Masked PSNR of the strip's frame, dB (`reference-ms`: the
six-way ceiling, the multiply-scattered lightmaps through the same shading; the last column: the flipbook where
it was baked):

{chr(10).join(rows)}

{strips}

"""


def ranking(report):
    """The methods from the closest to the ground truth down, with their masked PSNRs."""
    image = report["summary"]["image"]
    order = sorted(METHODS, key=lambda m: -(image[m]["psnr_masked_db"] or -math.inf))
    return " > ".join(f"{m} ({db(image[m]['psnr_masked_db'])} dB)" for m in order)


def quality_table(report):
    s = report["summary"]
    rows = ["| method | PSNR masked (dB) | mean of frames (dB) | PSNR full frame (dB) | MSE masked |",
            "|---|---|---|---|---|"]
    for m in METHODS:
        i = s["image"][m]
        rows.append(f"| {m} | **{db(i['psnr_masked_db'])}** | {db(i['mean_frame_psnr_masked_db'])} | "
                    f"{db(i['psnr_full_db'])} | {sci(i['mse_masked'])} |")
    lm = s["lightmap"]
    rows.append(f"| *neural lightmaps vs the baker's* | **{db(lm['psnr_masked_db'])}** | "
                f"{db(lm['mean_sample_psnr_masked_db'])} | {db(lm['psnr_full_db'])} | |")
    lm = s["lightmap_ms"]
    rows.append(f"| *neural lightmaps vs the multiply-scattered ones* | **{db(lm['psnr_masked_db'])}** | "
                f"{db(lm['mean_sample_psnr_masked_db'])} | {db(lm['psnr_full_db'])} | |")
    return "\n".join(rows)


def timing_table(report):
    medians = report["summary"]["median_ms"]
    methods = [m for m in ["simulation", *METHODS, "pathtrace"] if m in medians]
    stages = sorted({st for m in methods for st in medians[m]["stages_ms"]})
    rows = ["| stage | " + " | ".join(methods) + " |", "|---|" + "---|" * len(methods)]
    for st in stages:
        cells = [ms(medians[m]["stages_ms"].get(st)) if st in medians[m]["stages_ms"] else "" for m in methods]
        rows.append(f"| {st} | " + " | ".join(cells) + " |")
    rows.append("| **total (GPU timestamps)** | " + " | ".join(f"**{ms(medians[m]['total_ms'])}**"
                                                           for m in methods) + " |")
    rows.append("| wall clock of the render call | " +
                " | ".join(ms(medians[m].get("wall_ms")) for m in methods) + " |")
    return "\n".join(rows)


def equal_time_table(reports):
    rows = ["| ground truth | neural frame (ms) | path tracer spp in that time | its time (ms) | path tracer PSNR "
            "(dB) | neural PSNR (dB) | stand-in spp |", "|---|---|---|---|---|---|---|"]
    for label, r in reports:
        e = r["equal_time"]
        neural = e.get("neural") or {}
        rows.append(f"| {label} | {ms(e['budget_ms'])} | **{e['equal_time_spp']}** | {ms(e['equal_time_ms'])} | "
                    f"{db(e['equal_time']['psnr_masked_db'])} | {db(neural.get('psnr_masked_db'))} | "
                    f"{e['reference_spp']} |")
    return "\n".join(rows)


def over_budget(reports):
    """A sentence for the runs where even one sample per pixel takes longer than the neural frame."""
    over = [r["equal_time"] for r in reports if r["equal_time"]["equal_time_ms"] > r["equal_time"]["budget_ms"]]
    if not over:
        return ""
    worst = max(e["equal_time_ms"] / e["budget_ms"] for e in over)
    return (f"Where the count is 1 and its time exceeds the neural frame's, the path tracer cannot finish even one "
            f"sample per pixel in the budget (up to {worst:.1f}× over); its PSNR is that of 1 spp.")


def orbit_table(report):
    rows = ["| angle from the baked view | " + " | ".join(METHODS) + " |", "|---|" + "---|" * len(METHODS)]
    for f in report["per_frame"]:
        rows.append(f"| {f['view_angle_deg']:.0f}° | " +
                    " | ".join(db(f["image"][m]["psnr_masked_db"]) for m in METHODS) + " |")
    return "\n".join(rows)


def density_table(reports):
    rows = ["| density | lightmaps (dB) | " + " | ".join(METHODS) + " |", "|---|---|" + "---|" * len(METHODS)]
    for label, r in reports:
        s = r["summary"]
        rows.append(f"| {label} | {db(s['lightmap']['psnr_masked_db'])} | " +
                    " | ".join(db(s["image"][m]["psnr_masked_db"]) for m in METHODS) + " |")
    return "\n".join(rows)


def shadow_table(on, off):
    rows = ["| obstacle shadows | neural: shadow maps (ms) | neural: shade (ms) | neural total (ms) | "
            "neural PSNR (dB) | reference PSNR (dB) |", "|---|---|---|---|---|---|"]
    for label, r in [("on", on), ("off", off)]:
        n = r["summary"]["median_ms"]["neural"]
        rows.append(f"| {label} | {ms(n['stages_ms'].get('shadow maps'))} | {ms(n['stages_ms'].get('shade'))} | "
                    f"{ms(n['total_ms'])} | {db(r['summary']['image']['neural']['psnr_masked_db'])} | "
                    f"{db(r['summary']['image']['reference']['psnr_masked_db'])} |")
    return "\n".join(rows)


def main(argv):
    if len(argv) not in (3, 4):
        sys.exit("usage: eval_tables.py REPORT_DIR MACHINE.json [BENCH_TABLES.md]")
    d = argv[1]
    with open(argv[2]) as f:
        machine = json.load(f)
    multiple, single, orbit = load(d, "multiple"), load(d, "single"), load(d, "orbit")
    half, double = load(d, "density_0.5"), load(d, "density_2")
    on, off = load(d, "shadows_on"), load(d, "shadows_off")
    size = f"{multiple['size'][0]}×{multiple['size'][1]}"
    out = f"""# Results

Generated by `tools/results.sh` ({machine['date']}, commit `{machine['commit']}`); every table and plot on this
page comes from the `sixway eval --scene` reports it writes to `out/results/`. Do not edit by hand:
run `tools/results.sh` again.

{gallery_section(d)}**Machine.** {machine['cpu']} ({machine['cores']} cores), Vulkan device **{multiple['device']}**
({multiple['driver']}); load average {machine['load_before']} before the run, {machine['load_after']} after
(the machine is shared, so times vary with the load). The whole run, `{machine['settings']} tools/results.sh`,
took {machine['minutes']} minutes.

**Setting.** The scene is `{machine['scene']}` (a plume rising into a sphere, 24×32×24 lattice, an orbiting
directional light and a point light) rendered at {size} with {multiple['lightmap_size']}² lightmaps (the size
the shipped network was trained at), {multiple['frames']} frames of its live simulation, the shipped network
`weights/sixway-unet-ms.safetensors`. Ground truth is the volumetric path tracer at {multiple['pathtrace_spp']} spp.
The obstacles are drawn by every method and path-traced in the truth. Metrics follow [conventions.md, "Metrics"](conventions.md#metrics): PSNR on linear RGB clipped to [0, 1], **masked** to the pixels where
the ground truth's alpha > 0.01, the full-frame figure next to it; "PSNR masked" pools the squared errors of all
frames, "mean of frames" averages the frames' own PSNRs.

Methods: **neural** (guiding map → network → six-way shading), **reference** (the exact single-scattering baker's
lightmaps, same shading), **reference-ms** (multiply-scattered lightmaps: the exact single scattering plus the
higher orders path-traced at 64 samples per pixel, same shading: the axis-lit maps under full transport; with
`--fit-directions N`, **reference-fit**, the best six maps for the six-way blend, is measured too), **traditional** (lightmaps baked from frame 0's view, played back on a camera-facing billboard, as
games do), **traditional-ms** (the same flipbook baked with multiple scattering, as DCC tools bake it),
**guide-lit** (the guiding map's light used as all six lightmaps, its alpha as transparency: the network's input
without the network).

![side by side](results/strip.png)

*Frame {multiple['strip']['frame'] if multiple.get('strip') else '–'}: path tracer | neural | reference | traditional-ms |
the three errors |method − truth| × 4 (false colour, black = 0, white ≥ 0.25).*

## Final images against the path tracer

With multiple scattering ({multiple['pathtrace_orders']} orders: the real ground truth):

{quality_table(multiple)}

With single scattering (1 order: what the six-way lightmaps model; isolates the lightmaps from the missing
multiple scattering):

{quality_table(single)}

The smoke here is dense (σ_t = 25 /m at density 1, albedo 0.9), so multiple scattering brightens it beyond what
single-scattering lightmaps hold: the reference lightmaps reach {db(single['summary']['image']['reference']['psnr_masked_db'])} dB
against single scattering but {db(multiple['summary']['image']['reference']['psnr_masked_db'])} dB against the full path tracer. Against single scattering the order is {ranking(single)};
the gap between neural and reference is the network's error, the gap between guide-lit and neural what the
network adds to its input.

The same ceiling on every shipped scene (`tools/results/ms_ceiling.sh`, with lightmaps at half and at the full
frame size), on played-back OpenVDB scenes, and where the error of `reference-ms` sits (light directions between
the six basis directions, the glow's hue) are measured in
[reference-rendering.md, "The six-way ceiling under full transport"](reference-rendering.md#the-six-way-ceiling-under-full-transport).

![PSNR over frames](results/psnr_frames.png)

## Time per stage

Median per frame over the multiple-scattering run, milliseconds of GPU timestamps (`gpu::Sequence` stages; the
simulation's `StepTimes`), and the wall clock of each method's `ModeRenderer::render` call (upload, submit, wait,
readback). The timestamps are taken as each stage ends (on lavapipe too, since `gpu::Sequence` resolves each
one at once, docs/benchmarks.md), so the wall clock exceeds their sum by the host's uploads, waits and readbacks.

{timing_table(multiple)}

![time per stage](results/stage_times.png)

## Path tracer at equal time

The path tracer given the neural frame's wall-clock time (median over the run) at the last frame: renders of
1, 2, 4, ... spp until one takes longer, the count at the budget interpolated and rendered, all compared with a
high-sample stand-in traced with other random numbers (and the neural frame against the same stand-in).

{equal_time_table([(f"multiple scattering ({multiple['pathtrace_orders']} orders)", multiple),
                   ("single scattering (1 order)", single)])}

{over_budget([multiple, single])}

![equal time](results/equal_time.png)

## Camera orbiting away from the baked view

The camera orbits the plume at {orbit['camera_orbit_deg_per_frame']}° per frame (single-scattering ground
truth, {orbit['pathtrace_spp']} spp); the traditional flipbook stays baked from frame 0's view, the others
follow the camera.

{orbit_table(orbit)}

![PSNR vs angle](results/psnr_angle.png)

## Density scale

The smoke's extinction scaled (σ_t × scale: optically thinner or thicker smoke than the network saw in
training), {half['frames']} frames each, single-scattering ground truth, masked PSNR:

{density_table([("× 0.5", half), ("× 1", single), ("× 2", double)])}

(× 1 is the single-scattering run above, over its {single['frames']} frames.)

## Obstacle shadows on and off

The obstacles drawn in every method and path-traced in the truth, {on['frames']} frames, with their shadows and
without them (`--no-shadows`: in every method and in the truth).

{shadow_table(on, off)}
"""
    ablations = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "results",
                             "ablations.md")
    out += """
## Ablations: guide lights and channel adapters

Networks retrained for the same budget (1,000 steps of the shipped recipe, `tools/train_configs/ablations/`) on
the same sequences, cameras and targets (`tools/datasets/cpu_small.json`; the guide-light variants only change
the guiding map, `tools/datasets/ablations/`), measured on the held-out splits by the C++ pipeline
(`sixway eval --dataset`, lightmap PSNR against the baker, masked). Made by `tools/ablations.sh` (1.5–2 hours
here, so not part of the default run; `ABLATIONS=1 tools/results.sh` runs it first). The baseline here is the
shipped architecture at this shorter budget, not the shipped weights (2,500 steps). Trained and measured on
the machine above (one CPU thread per training, shared with other jobs, so the training minutes vary with the
load). One training run per variant: the spread between runs with other seeds was not measured, so differences
of a few tenths of a dB are no evidence of a difference.

"""
    if os.path.exists(ablations):
        with open(ablations) as f:
            out += f.read()
    else:
        out += "Not run yet on this machine: `tools/ablations.sh`.\n"
    if len(argv) == 4 and os.path.exists(argv[3]):
        # The tables themselves go to docs/benchmarks.md (results.sh writes them between its markers); here the
        # run's device, date and load, and where the tables are.
        with open(argv[3]) as f:
            head = f.read().split("### Simulation", 1)[0].rstrip()
        out += ("\n## Benchmarks (`sixway bench`)\n\n" + head + "\n\nThe tables of this run: "
                "[benchmarks.md](benchmarks.md#the-latest-run-on-lavapipe-toolsresultssh).\n")
    print(out, end="")


if __name__ == "__main__":
    main(sys.argv)
