#!/usr/bin/env python3
"""The recipes of docs/data.md, run: a fold's tables and its recording read back in Python.

Runs the README's fold with `--table` as CSV and as Parquet and `--save`, then

* loads the series and the tension profiles with pandas, each in one line, and checks what
  docs/data.md says of them: float64 values, y pointing down (the free end falls to positive
  y), the energy kept (midpoint), one profile per frame from s = 0 to s < 1, the same numbers
  in both formats;
* reads the `.rrd` with Rerun 0.36's `RrdReader` and checks that its `/energy/total` is the
  table's energy at the same instants (the recording holds float64 scalars).

    scripts/table-check.py [--rope PATH] [--keep DIR]

Needs `pip install pandas pyarrow rerun-sdk==0.36.3 datafusion==54.0.0` (the reader's
DataFrame needs DataFusion, which rerun-sdk does not install). Where one is missing it says
so and exits 0 as SKIPPED; CI installs them in a virtual environment.
"""

import argparse
import pathlib
import subprocess
import sys
import tempfile

FOLD = ["--scene", "fold", "--gap", "0.02", "--segments", "200"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rope", default="target/release/rope")
    parser.add_argument("--keep", help="write the files here instead of a temporary folder")
    args = parser.parse_args()
    try:
        import numpy as np
        import pandas as pd
        import pyarrow  # noqa: F401  (pandas reads Parquet through it)
        import rerun as rr
        import datafusion  # noqa: F401  (RrdReader's DataFrame)
    except ImportError as missing:
        print(f"table-check: SKIPPED ({missing}; pip install pandas pyarrow "
              "rerun-sdk==0.36.3 datafusion==54.0.0)")
        return 0
    with tempfile.TemporaryDirectory() as scratch:
        out = pathlib.Path(args.keep or scratch)
        out.mkdir(parents=True, exist_ok=True)
        for table in ["fold.csv", "fold.parquet"]:
            subprocess.run(
                [args.rope, "run", *FOLD, "--save", str(out / "fold.rrd"),
                 "--table", str(out / table)],
                check=True, stderr=subprocess.DEVNULL)

        # The recipe: one line a table.
        series = pd.read_parquet(out / "fold.parquet")
        profiles = pd.read_parquet(out / "fold-profiles.parquet")
        from_csv = pd.read_csv(out / "fold.csv")

        numbers = series.drop(columns=["scene", "method"])
        assert all(t == np.float64 for t in numbers.dtypes), numbers.dtypes
        assert list(from_csv.columns) == list(series.columns), from_csv.columns
        assert np.allclose(from_csv[numbers.columns], numbers, rtol=0, atol=0,
                           equal_nan=True), "CSV and Parquet differ"
        assert series.method.eq("midpoint").all() and len(series) == 181, len(series)
        # y points down: the free end falls from y = 0 to positive y.
        assert series.tip_y.iloc[0] == 0 or abs(series.tip_y.iloc[0]) < 1e-12
        assert series.tip_y.max() > 0.9, series.tip_y.max()
        # midpoint keeps the energy.
        assert series.energy_deviation.abs().max() < 1e-9, series.energy_deviation.abs().max()
        last = profiles[profiles.time == profiles.time.max()]
        assert last.s.iloc[0] == 0 and last.s.max() < 1 and len(last) == 201, last.s.describe()
        assert profiles.groupby("time").size().eq(201).all()
        # The pull at the support is the profile's first value.
        first = profiles.groupby("time").tension.first().to_numpy()
        assert np.array_equal(first, series.support_tension.to_numpy()), "F(0) differs"

        # The recording, read back with Rerun's own reader.
        store = rr.experimental.RrdReader(str(out / "fold.rrd")).stream().collect()
        energy = store.reader(index="sim_time", contents="/energy/total").to_pandas()
        recorded = np.array([v[0] for v in energy["/energy/total:Scalars:scalars"]])
        times = energy["sim_time"].dt.total_seconds().to_numpy()
        table = series.set_index("time").energy.reindex(np.round(times, 9), method="nearest")
        assert len(recorded) == len(series), (len(recorded), len(series))
        assert np.allclose(recorded, table.to_numpy(), rtol=0, atol=1e-12), "rrd and table differ"
        print(f"table-check: ok ({len(series)} frames, {len(profiles)} profile rows; "
              f"CSV, Parquet and the .rrd agree)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
