"""Independent re-measurement of the settings `terrace tradeoff` chose (cli_checks.sh tradeoff).

  tradeoff_recheck.py plan TRADEOFF.json SCENE   a sweep file: the chosen DMD and SMD settings and
                                                 the reference, 8 new seeds each
  tradeoff_recheck.py check TRADEOFF.json DIR    each chosen setting's bias on every observable,
                                                 from the sweep's runs in DIR, is not outside its
                                                 tolerance at 2 standard errors
"""
import json
import math
import sys

SEEDS = list(range(201, 209))


def plan(tradeoff, scene):
    t = json.load(open(tradeoff))
    settings = {s["setting"]: s for s in t["settings"]}
    cases, labels = [], []
    for name in (t["cost"]["dmd"], t["cost"]["smd"]):
        s = settings[name]
        if s["engine"] == "dmd":
            c = {"engine": "dmd", "dmd.model": "smoothed", "dmd.dV": s["dV_kT"]}
            if s["ladder"] == "dmd-optimal":
                c["dmd.terraces"] = {"levels": "optimal", "values": "boltzmann", "n": 0}
        else:
            c = {"engine": "smd", "smd.scheme": s["ladder"][4:], "smd.dt_fs": s["dt_fs"]}
        cases.append(c)
        labels.append(name)
    ref = t["reference"]
    cases.append({"engine": "smd", "smd.scheme": "yoshida4", "smd.dt_fs": ref["dt_fs"]})
    labels.append("reference")
    print(json.dumps({"scene": scene, "axes": [{"cases": cases, "labels": labels}],
                      "seeds": SEEDS}))


def value(summary, observable, estimator, bodies, epsilon):
    if observable == "u":
        block = summary["configurational"] if estimator == "configurational" else summary
        return block["potential_energy_mean"] / (bodies * epsilon)
    if observable == "p":
        if estimator == "configurational":
            return summary["configurational"]["pressure_reduced"]
        return summary["pressure"]["mean_reduced"]
    raise SystemExit("tradeoff_recheck.py checks u and p only, not " + observable)


def mean_and_se(x):
    m = sum(x) / len(x)
    return m, math.sqrt(sum((v - m) ** 2 for v in x) / (len(x) - 1) / len(x))


def check(tradeoff, directory):
    t = json.load(open(tradeoff))
    settings = {s["setting"]: s for s in t["settings"]}
    ok = True
    for name in (t["cost"]["dmd"], t["cost"]["smd"]):
        for b in settings[name]["biases"]:
            obs, est = b["observable"], b["estimator"]
            runs = {}
            for label, e in ((name, est), ("reference", "own")):
                xs = []
                for seed in SEEDS:
                    s = json.load(open(f"{directory}/{label}_seed-{seed}/summary.json"))
                    scene = json.load(open(f"{directory}/{label}_seed-{seed}/scene.json"))
                    xs.append(value(s, obs, e, s["n_bodies"], scene["potential"]["epsilon"]))
                runs[label] = mean_and_se(xs)
            bias = runs[name][0] - runs["reference"][0]
            se = math.hypot(runs[name][1], runs["reference"][1])
            within = abs(bias) - 2 * se < b["tolerance"]
            print(f"{name} {obs} ({est}): bias {bias:.4g} +- {se:.2g}, tolerance "
                  f"{b['tolerance']:.4g}: {'within' if within else 'OUTSIDE'}")
            ok = ok and within
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    if sys.argv[1] == "plan":
        plan(sys.argv[2], sys.argv[3])
    else:
        check(sys.argv[2], sys.argv[3])
