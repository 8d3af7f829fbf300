"""``python -m mjcfbuild``: the command line."""

from mjcfbuild.cli import main

if __name__ == "__main__":
    main()
