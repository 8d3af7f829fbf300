"""The machine-wide cache of step products: where they are kept, and whether one is usable.

Below the steps that store and fetch products, the sharing package that moves them between
machines, and the engine and commands that size and prune the cache.
"""
