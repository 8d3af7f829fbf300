"""The work of each kind of build task.

Each module has one ``run(payload) -> dict`` function. Tasks call it in the build process or in
a worker process (for steps that run C++ code); the payload and the result are plain JSON, and
the result's ``outputs`` maps every file the step wrote to its MD5, so the next build can tell
an output that was edited or damaged by hand.
"""
