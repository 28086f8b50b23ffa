"""``python -m halfedge_edu ...``: the same command line as ``halfedge-edu ...``."""

from halfedge_edu.cli import main

if __name__ == "__main__":
    raise SystemExit(main())
