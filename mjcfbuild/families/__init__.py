"""The task families of a build, one module each: its payload's use, its format and tools,
where it runs, and the doit tasks it declares. :mod:`mjcfbuild.families.registry` lists them in
graph order; each family's step (its ``run`` function) is in :mod:`mjcfbuild.steps`.
"""
