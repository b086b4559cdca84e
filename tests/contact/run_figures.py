"""Reading a `pcsim run` result folder in the window tests
(test_run_window.sh, test_run_window_wind.sh): its summary.json, one
pantograph's EN 50318 figures by key, its contact force and position."""
import json

import h5py


def summary(folder):
    with open(f"{folder}/summary.json") as f:
        return json.load(f)


def figures(folder, pantograph="pantograph"):
    return {f["key"]: f["value"] for f in summary(folder)["en50318"][pantograph]["figures"]}


def force_and_position(folder, pantograph="pantograph"):
    with h5py.File(f"{folder}/results.h5") as f:
        group = f[f"/pantographs/{pantograph}"]
        return group["contact_force"][:], group["position"][:]


class Runs:
    """The result folders of one test, by run name: d/<name>."""

    def __init__(self, folder):
        self.folder = folder

    def summary(self, name):
        return summary(f"{self.folder}/{name}")

    def figures(self, name, pantograph="pantograph"):
        return figures(f"{self.folder}/{name}", pantograph)

    def force_and_position(self, name, pantograph="pantograph"):
        return force_and_position(f"{self.folder}/{name}", pantograph)
