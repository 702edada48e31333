#!/usr/bin/python3
"""The held-out table of tools/results/heldout.sh, printed to stdout as markdown.

Usage: heldout_table.py REPORT_DIR LABEL [LABEL ...]

REPORT_DIR/LABEL/ holds one `sixway eval --dataset` report per family (named after its data directory). A row per
family: masked PSNR on the unseen sequences / the unseen camera, with the emissive channel's (E) where the family
emits; then the samples pooled (squared errors weighted by sample count, as one set): over the trained families'
held-out splits (the 33 dB target) and over every family with the unseen one (its own target is to be
within 2 dB of the first).
"""
import json
import math
import os
import sys

# Data directory (slashes as "_") and the name the model card gives it, in the card's order.
FAMILIES = [
    ("inputs", "plume"), ("families_explosion", "explosion"), ("families_jet_plume", "jet"),
    ("families_jet_bunny", "jet + bunny"), ("families_moving_sphere", "moving sphere"),
    ("families_young_plume", "young plume"), ("families_young_jet_plume", "young jet"),
    ("families_young_jet_bunny", "young jet + bunny"), ("families_young_moving_sphere", "young moving sphere"),
    ("families_young_explosion", "young explosion"), ("families_young_explosion_views", "young explosion, 16 views"),
    ("families_young_explosion_start", "young explosion, first frames"),
    ("families_young128_plume", "young plume, 128²"), ("families_young128_jet_plume", "young jet, 128²"),
    ("families_young128_jet_bunny", "young jet + bunny, 128²"),
    ("families_young128_moving_sphere", "young moving sphere, 128²"),
    ("families_young128_explosion", "young explosion, 128²"),
    ("families_young_lattice_jet_plume", "young jet, 128², scene lattice"),
    ("families_young_lattice_jet_bunny", "young jet + bunny, 128², scene lattice"),
    ("families_young_lattice_moving_sphere", "young moving sphere, 128², scene lattice"),
    ("families_young_full_jet_plume", "young jet, scene lattice, full-resolution MS targets"),
    ("families_young_full_jet_bunny", "young jet + bunny, scene lattice, full-resolution MS targets"),
    ("families_young_full_moving_sphere", "young moving sphere, scene lattice, full-resolution MS targets"),
    ("families_young_full64_plume", "young plume, full-resolution MS targets"),
    ("families_young_full64_jet_plume", "young jet, full-resolution MS targets"),
    ("families_young_full64_jet_bunny", "young jet + bunny, full-resolution MS targets"),
    ("families_young_full64_moving_sphere", "young moving sphere, full-resolution MS targets"),
    ("families_young_full64_explosion", "young explosion, full-resolution MS targets"),
    ("families_young_full128_plume", "young plume, 128², full-resolution MS targets"),
    ("families_young_full128_jet_plume", "young jet, 128², full-resolution MS targets"),
    ("families_young_full128_jet_bunny", "young jet + bunny, 128², full-resolution MS targets"),
    ("families_young_full128_moving_sphere", "young moving sphere, 128², full-resolution MS targets"),
    ("families_young_full128_explosion", "young explosion, 128², full-resolution MS targets"),
    ("families_chimney_wind", "chimney in wind (unseen family)"),
]
SPLITS = ["heldout_sequence", "heldout_camera"]
UNSEEN_FAMILY = "families_chimney_wind"  # no sample of it is trained on: every sequence is held out


def mse(psnr_db):
    return 10.0 ** (-psnr_db / 10.0)


def psnr(error):
    return -10.0 * math.log10(error)


def cell(report):
    if report is None:
        return "–"
    parts, glows = [], []
    for split in SPLITS:
        result = report["splits"].get(split)
        if not result or not result.get("samples"):
            continue
        parts.append(f"{result['psnr_masked_db']:.2f}")
        emissive = result["channels_psnr_masked_db"].get("emissive")
        if emissive is not None and emissive < 45:  # without emission the map is near zero: 50-80 dB
            glows.append(f"{emissive:.1f}")
    text = " / ".join(parts) if parts else "–"
    return text + (f" (E {' / '.join(glows)})" if glows else "")


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: heldout_table.py REPORT_DIR LABEL [LABEL ...]")
    root, labels = sys.argv[1], sys.argv[2:]
    reports = {}
    for label in labels:
        for key, _ in FAMILIES:
            path = os.path.join(root, label, key + ".json")
            if os.path.isfile(path):
                with open(path) as f:
                    reports[label, key] = json.load(f)
    print("| family | " + " | ".join(labels) + " |")
    print("|---|" + "---|" * len(labels))
    for key, name in FAMILIES:
        if any((label, key) in reports for label in labels):
            print(f"| {name} | " + " | ".join(cell(reports.get((label, key))) for label in labels) + " |")
    # Pooled over the families every network has, per split: the sample-weighted mean of the masked MSE.
    common = [key for key, _ in FAMILIES if all((label, key) in reports for label in labels)]
    trained = [key for key in common if key != UNSEEN_FAMILY]
    for keys, name in ((trained, "trained families"), (common, "with the unseen family")):
        pooled = [pooled_cell([reports[label, key] for key in keys]) for label in labels]
        print(f"| pooled, {name} ({len(keys)} sets, sample-weighted) | " + " | ".join(pooled) + " |")


def pooled_cell(family_reports):
    figures = []
    for split in SPLITS:
        total = count = 0
        for report in family_reports:
            result = report["splits"].get(split)
            if result and result.get("samples"):
                total += mse(result["psnr_masked_db"]) * result["samples"]
                count += result["samples"]
        figures.append(f"{psnr(total / count):.2f}" if count else "–")
    return " / ".join(figures)

if __name__ == "__main__":
    main()
