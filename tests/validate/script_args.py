"""The arguments shared by the checks of the validation scripts: --source (the repository, whose
validation/ folder is put on the import path so that the check calls the script's own functions)
and --out (where the check writes its run folders)."""
import argparse
import os
import sys


def parse():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(a.source, "validation"))
    return a
