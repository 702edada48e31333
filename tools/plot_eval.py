#!/usr/bin/python3
"""Plots of `sixway eval --scene` reports, for docs/results.md.

  plot_eval.py frames REPORT OUT.png        final-image PSNR vs the path tracer over the frames, per method
  plot_eval.py stages REPORT OUT.png        median GPU time per stage, stacked, per method (and the simulation)
  plot_eval.py angle REPORT OUT.png         PSNR vs the view's angle from the flipbook's baked view
  plot_eval.py equal-time REPORT OUT.png    path-tracer noise vs its time, with the neural frame's time and PSNR

Reads only the report's JSON (src/eval/scene_eval.h); small PNGs (about 6 x 3.2 in at 100 dpi).
"""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"neural": "C0", "reference": "C2", "reference-ms": "C5", "traditional": "C1", "traditional-ms": "C6",
           "guide-lit": "C3", "pathtrace": "C4",
           "simulation": "C7"}


def value(v):
    return math.nan if v is None else v


def psnr_series(report, method):
    return [value(f["image"][method]["psnr_masked_db"]) for f in report["per_frame"]]


def finish(fig, ax, out, title):
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)


def plot_frames(report, out):
    fig, ax = plt.subplots(figsize=(6, 3.2))
    frames = [f["frame"] for f in report["per_frame"]]
    for method in report["methods"]:
        ax.plot(frames, psnr_series(report, method), marker=".", label=method, color=COLOURS.get(method))
    lightmap = [value(f["lightmap"]["psnr_masked_db"]) for f in report["per_frame"]]
    ax.plot(frames, lightmap, linestyle="--", color="C0", alpha=0.6, label="neural lightmaps vs baker")
    ax.set_xlabel("frame")
    ax.set_ylabel("PSNR, masked (dB)")
    finish(fig, ax, out, f"vs the path tracer ({report['pathtrace_spp']} spp, "
                         f"{report['pathtrace_orders']} orders)")


def plot_stages(report, out):
    medians = report["summary"]["median_ms"]
    methods = [m for m in ["simulation", *report["methods"], "pathtrace"] if m in medians]
    stages = sorted({s for m in methods for s in medians[m]["stages_ms"]})
    fig, ax = plt.subplots(figsize=(7, 3.4))
    bottoms = [0.0] * len(methods)
    cmap = plt.get_cmap("tab20")
    for k, stage in enumerate(stages):
        heights = [medians[m]["stages_ms"].get(stage, 0.0) for m in methods]
        if not any(heights):
            continue
        ax.bar(methods, heights, bottom=bottoms, label=stage, color=cmap(k % 20))
        bottoms = [b + h for b, h in zip(bottoms, heights)]
    ax.set_ylabel("median GPU time per frame (ms)")
    ax.tick_params(axis="x", labelsize=8, rotation=20)
    ax.legend(fontsize=6, ncol=2, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    ax.set_title("time per stage (GPU timestamps)", fontsize=9)
    ax.grid(alpha=0.3, axis="y")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)


def plot_angle(report, out):
    fig, ax = plt.subplots(figsize=(6, 3.2))
    angles = [f["view_angle_deg"] for f in report["per_frame"]]
    for method in report["methods"]:
        ax.plot(angles, psnr_series(report, method), marker=".", label=method, color=COLOURS.get(method))
    ax.set_xlabel("camera angle from the flipbook's baked view (degrees)")
    ax.set_ylabel("PSNR, masked (dB)")
    finish(fig, ax, out, "camera orbiting away from the baked view")


def plot_equal_time(report, out):
    study = report["equal_time"]
    fig, ax = plt.subplots(figsize=(6, 3.2))
    ms = [p["ms"] for p in study["curve"]]
    psnr = [value(p["psnr_masked_db"]) for p in study["curve"]]
    ax.plot(ms, psnr, marker="o", color=COLOURS["pathtrace"], label="path tracer, 1, 2, 4, ... spp")
    for p in study["curve"]:
        ax.annotate(str(p["spp"]), (p["ms"], value(p["psnr_masked_db"])), fontsize=7,
                    textcoords="offset points", xytext=(3, -9))
    ax.axvline(study["budget_ms"], color=COLOURS["neural"], linestyle=":", label="neural frame time")
    if study.get("neural"):
        ax.plot([study["budget_ms"]], [value(study["neural"]["psnr_masked_db"])], marker="*", markersize=12,
                color=COLOURS["neural"], linestyle="none", label="neural")
    ax.set_xscale("log")
    ax.set_xlabel("time (ms, host clock)")
    ax.set_ylabel(f"PSNR vs {study['reference_spp']} spp (dB)")
    finish(fig, ax, out, "path tracer at equal time")


PLOTS = {"frames": plot_frames, "stages": plot_stages, "angle": plot_angle, "equal-time": plot_equal_time}


def main(argv):
    if len(argv) != 4 or argv[1] not in PLOTS:
        sys.exit(f"usage: plot_eval.py {{{'|'.join(PLOTS)}}} REPORT.json OUT.png")
    try:
        with open(argv[2]) as f:
            report = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"plot_eval.py: {argv[2]}: {e}")
    PLOTS[argv[1]](report, argv[3])


if __name__ == "__main__":
    main(sys.argv)
