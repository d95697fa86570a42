"""Gather a corpus of public CAD files for bench/sweep.py from Debian's archive.

    /usr/bin/python3 bench/fetch_corpus.py corpus/      # then: bench/sweep.py corpus/

Downloads (apt-get download, no installation, nothing outside the Debian
archive) the packages below and extracts their STEP / IGES / BRep / FCStd
files (gzip ones unpacked) into the folder, one subfolder per package. The
files are public test and example data of OpenCASCADE (occt-misc: OCCT's
sample shapes, among them the 312 x 323-pole terrain, a wing, a bottle and
freeform furniture), Gmsh (gmsh-doc: tutorial and demo models), Netgen
(netgen-doc) and FreeCAD (freecad-common: test documents and IDF parts). The
repository does not ship them.
"""

import argparse
import gzip
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile

PACKAGES = ("occt-misc", "gmsh-doc", "netgen-doc", "freecad-common")
EXTENSIONS = (".step", ".stp", ".iges", ".igs", ".brep", ".brp", ".fcstd")


def cad_name(member):
    """The file name to extract member as, or None when it is not CAD data."""
    name = os.path.basename(member)
    low = name.lower()
    if low.endswith(".gz"):
        low, name = low[:-3], name[:-3]
    return name if low.endswith(EXTENSIONS) else None


def extract(deb, folder):
    """CAD files of one .deb into folder; returns how many."""
    count = 0
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(["dpkg-deb", "--fsys-tarfile", deb], check=True,
                       stdout=open(os.path.join(tmp, "data.tar"), "wb"))
        with tarfile.open(os.path.join(tmp, "data.tar")) as tar:
            for member in tar.getmembers():
                name = cad_name(member.name) if member.isfile() else None
                if name is None:
                    continue
                os.makedirs(folder, exist_ok=True)
                target = os.path.join(folder, name)
                if os.path.exists(target):  # the same file twice (gmsh demos): keep one
                    continue
                src = tar.extractfile(member)
                with open(target, "wb") as out:
                    shutil.copyfileobj(gzip.GzipFile(fileobj=src) if member.name.endswith(".gz")
                                       else src, out)
                count += 1
    return count


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("--packages", nargs="*", default=list(PACKAGES))
    args = ap.parse_args(argv)
    os.makedirs(args.folder, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        os.chmod(tmp, 0o777)  # apt's sandbox user writes here
        for pkg in args.packages:
            got = subprocess.run(["apt-get", "download", pkg], cwd=tmp, capture_output=True,
                                 text=True)
            debs = [f for f in os.listdir(tmp) if f.startswith(pkg + "_") and f.endswith(".deb")]
            if got.returncode != 0 or not debs:
                print(f"{pkg}: download failed ({got.stderr.strip()[-200:]}); run "
                      "'apt-get update' first", file=sys.stderr)
                continue
            n = extract(os.path.join(tmp, debs[0]), os.path.join(args.folder, pkg))
            print(f"{pkg}: {n} CAD files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
