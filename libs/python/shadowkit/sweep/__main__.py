"""python3 -m shadowkit.sweep SPEC --out DIR [--scheduler tcp://HOST:8786 | --local-workers N]"""
import sys

from .cli import main

sys.exit(main())
