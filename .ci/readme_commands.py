"""Print the shell commands of README's "On a fresh machine" section, one per line."""

import re
import sys
from pathlib import Path

text = Path(sys.argv[1]).read_text()
section = text.split("## On a fresh machine", 1)[1].split("\n## ", 1)[0]
blocks = re.findall(r"```sh\n(.*?)```", section, re.S)
# The first two blocks are the install-and-build and the tests; later ones (lint) CI runs itself.
for block in blocks[:2]:
    print(" ".join(block.split()))
