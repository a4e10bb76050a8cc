"""RocketPy 1.13's SensitivityModel on the completed rows of a karman study's samples.csv:
the reference figures of crates/cli/tests/sensitivity.rs.

    python sensitivity.py DIR/samples.csv OUTPUT,OUTPUT,... INPUT,INPUT,...

(needs `pip install rocketpy==1.13.0 statsmodels prettytable`).
"""
import csv, sys, json
import numpy as np
import rocketpy
from rocketpy.sensitivity import SensitivityModel
path, outputs = sys.argv[1], sys.argv[2].split(",")
inputs = sys.argv[3].split(",")
rows = [r for r in csv.DictReader(open(path)) if r["status"] == "ok"]
X = np.array([[float(r[c]) for c in inputs] for r in rows])
Y = np.array([[float(r[c]) for c in outputs] for r in rows])
model = SensitivityModel(inputs, outputs)
model.fit(X, Y)
from importlib.metadata import version
res = {"rocketpy": version("rocketpy")}
for o in outputs:
    info = model.target_variables_info[o]
    res[o] = {"shares": [info["sensitivity"][p] for p in inputs], "lae": info["LAE"], "sd": info["sd"],
              "coef": list(info["model"].params[1:])}
print(json.dumps(res, indent=1))
