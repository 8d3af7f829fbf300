"""Sharing work beyond one machine: a remote product cache and a Dask executor.

Nothing here is imported by a build that has nothing to compute: the settings are parsed with
the standard library only (:mod:`mjcfbuild.sharing_settings`, below the manifest that
validates them), and fsspec, s3fs and dask are imported when a product is first
fetched, uploaded or sent to a cluster.
"""
