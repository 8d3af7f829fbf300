"""``mjcfbuild diff``: what changed in the model between two builds, grouped for a reviewer.

``snapshot`` reads one build folder into plain data (the model compiled with MuJoCo, the
build's state files, its pictures); ``compare`` turns two snapshots into grouped changes;
``render`` writes them as text, Markdown or JSON; ``revisions`` builds git revisions of a
description repo in scratch folders.
"""
