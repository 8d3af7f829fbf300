"""The build engine: mjcfbuild's tasks on doit, worker processes, hashing and progress."""
