#!/usr/bin/env python3
"""Per-kernel floors from an Nsight Compute run: what bounds each of the frame's kernels.

Run the bench under ncu with these metrics (the GPU machine has ncu at /usr/local/cuda/bin):

  ncu --csv --page raw --metrics gpu__time_duration.sum,smsp__inst_executed.sum,dram__bytes.sum,\
lts__t_bytes.sum,sm__cycles_elapsed.avg.per_second --launch-skip 400 --launch-count 300 \
    build-gpu/app/bench/hdrfusion-bench --frames 12 --device cuda --voxel compact --case 640x480x20 > ncu.csv

then `tools/ncu_kernels.py ncu.csv [--bandwidth GB/s] [--clock MHz]`. For each kernel (launches
of the same function together) it prints the mean time and two floors:

- issue: its warp instructions at one instruction per cycle on each of the GPU's schedulers
  (SMs x schedulers per SM, from the device attributes ncu records) at the given clock (default:
  the clock ncu ran the kernel at; ncu fixes the clocks, so its times are longer than the
  bench's);
- DRAM: the bytes it moved to and from the GPU's memory at --bandwidth (default 2800 GB/s, an
  H100's device-to-device copy as the bench measures it).

A kernel far above both is bound by latency: chains of dependent work, or too few warps.
"""
import argparse
import collections
import csv
import re
import sys


def number(text):
    return float(text.replace(",", "")) if text not in ("", "n/a") else 0.0


def short_name(name):
    name = name.replace("(anonymous namespace)::", "").replace("<unnamed>::", "")
    # par::PixelKernel<void volume::RaycastInto<...>(...)::[lambda...]> -> volume::RaycastInto
    inner = re.search(r"(?:PixelKernel|IndexKernel)<(?:void )?(?:[\w:]+ )?([\w:]+?)(?:<|\()", name)
    if inner:
        return inner.group(1)
    return re.sub(r"^void ", "", re.sub(r"[<(].*", "", name))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv")
    ap.add_argument("--bandwidth", type=float, default=2800.0, help="GB/s for the DRAM floor")
    ap.add_argument("--clock", type=float, default=0.0, help="MHz for the issue floor (default: ncu's)")
    a = ap.parse_args()
    rows = [r for r in csv.reader(open(a.csv, newline="")) if len(r) > 5]
    if len(rows) < 3 or "Kernel Name" not in rows[0]:
        sys.exit(f"{a.csv}: not an ncu --csv --page raw report (no 'Kernel Name' column)")
    head = {h: i for i, h in enumerate(rows[0])}
    need = ["gpu__time_duration.sum", "smsp__inst_executed.sum", "dram__bytes.sum",
            "sm__cycles_elapsed.avg.per_second", "device__attribute_multiprocessor_count",
            "device__attribute_num_schedulers_per_multiprocessor"]
    missing = [m for m in need if m not in head]
    if missing:
        sys.exit(f"{a.csv}: the report lacks {', '.join(missing)} (run ncu with the metrics above)")
    units = rows[1]
    if units[head["gpu__time_duration.sum"]] != "ns" or units[head["dram__bytes.sum"]] != "byte":
        sys.exit(f"{a.csv}: unexpected units {units[head['gpu__time_duration.sum']]}, {units[head['dram__bytes.sum']]}")
    kernels = collections.OrderedDict()
    for r in rows[2:]:
        k = kernels.setdefault(short_name(r[head["Kernel Name"]]), collections.Counter())
        k["n"] += 1
        k["ns"] += number(r[head["gpu__time_duration.sum"]])
        k["inst"] += number(r[head["smsp__inst_executed.sum"]])
        k["dram"] += number(r[head["dram__bytes.sum"]])
        k["hz"] += number(r[head["sm__cycles_elapsed.avg.per_second"]])
        k["schedulers"] = number(r[head["device__attribute_multiprocessor_count"]]) * number(
            r[head["device__attribute_num_schedulers_per_multiprocessor"]])
    print(f"| kernel | launches | us each | warp instructions (M) | issue floor us | x issue | DRAM MB | DRAM floor us | x DRAM |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, k in sorted(kernels.items(), key=lambda kv: -kv[1]["ns"]):
        n = k["n"]
        us = k["ns"] / n / 1e3
        hz = a.clock * 1e6 if a.clock > 0 else k["hz"] / n
        issue = k["inst"] / n / (k["schedulers"] * hz) * 1e6
        dram_mb = k["dram"] / n / 1e6
        dram_us = dram_mb / a.bandwidth * 1e3
        print(f"| {name} | {n} | {us:.1f} | {k['inst'] / n / 1e6:.2f} | {issue:.1f} | {us / issue if issue else 0:.1f} | "
              f"{dram_mb:.2f} | {dram_us:.2f} | {us / dram_us if dram_us else 0:.0f} |")


if __name__ == "__main__":
    main()
