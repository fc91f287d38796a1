#!/usr/bin/env python3
"""Scores a `scanloc localise` run against a mapping session's run of the same log: the posture of
each scan (matched by timestamp) against the session's, and when the posture was first confirmed.

  scripts/localise_agreement.py SESSION_RUN LOCALISE_RUN [--settle N] [--splice-at K]

Prints one JSON object: scans and log seconds to the first confirmed posture, the median, 95th
percentile and maximum distance (m) over the scans after the first N (default 30; a scan without a
posture counts as infinitely far), and, with --splice-at K (the first scan of a spliced log's
second stretch), the scans after K until the posture was confirmed again. `confirmed_far_scans`
counts the scans (from the first) stated "confirmed" more than 1 m from the session's posture: a
wrong place confirmed, where "ambiguous" would have been honest.
"""
import argparse
import json
import math


def tum(path):
    poses = {}
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        t, x, y = (float(v) for v in line.split()[:3])
        poses[round(t, 6)] = (x, y)
    return poses


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("session")
    parser.add_argument("localise")
    parser.add_argument("--settle", type=int, default=30)
    parser.add_argument("--splice-at", type=int)
    a = parser.parse_args()
    reference = tum(a.session + "/trajectory.tum")
    records = [json.loads(line) for line in open(a.localise + "/iterations.jsonl")]
    summary = json.load(open(a.localise + "/summary.json"))
    errors, reconfirmed, confirmed_far = [], None, 0
    for r in records:
        truth = reference.get(round(r["timestamp_s"], 6))
        p = r["T_world_robot"]
        if truth is not None and r.get("state") == "confirmed" and r.get("posed", True):
            confirmed_far += math.hypot(p["x_m"] - truth[0], p["y_m"] - truth[1]) > 1.0
        if a.splice_at is not None and reconfirmed is None and r["index"] >= a.splice_at \
                and r.get("state") == "confirmed" and any(
                    q.get("lost") for q in records[a.splice_at:r["index"]]):
            reconfirmed = r["index"] - a.splice_at
        if r["index"] < a.settle or truth is None:
            continue
        errors.append(math.hypot(p["x_m"] - truth[0], p["y_m"] - truth[1]) if r.get("posed", True)
                      else math.inf)
    errors.sort()
    n = len(errors)
    at = lambda q: errors[min(n - 1, max(0, math.ceil(q * n) - 1))] if n else None
    searches = [r["search"]["time_s"] for r in records if "search" in r]
    print(json.dumps({
        "scans": len(records),
        "first_confirmed_scan": summary.get("first_confirmed_scan"),
        "seconds_to_confirm": summary.get("seconds_to_confirm"),
        "compared": n,
        "median_m": at(0.5), "p95_m": at(0.95), "max_m": errors[-1] if n else None,
        "global_searches": len(searches),
        "search_wall_s_mean": sum(searches) / len(searches) if searches else None,
        "search_wall_s_max": max(searches) if searches else None,
        "lost": summary.get("lost_stretches"),
        "scans_to_reconfirm_after_splice": reconfirmed,
        "confirmed_far_scans": confirmed_far,
    }))


if __name__ == "__main__":
    main()
