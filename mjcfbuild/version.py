"""mjcfbuild's version, in a module of its own, at the bottom of the layers.

Modules that record the version (the command line's ``--version``, step versions, the
package's files) import it from here: the package's ``__init__`` reaches up to the build API,
so importing ``mjcfbuild`` itself from inside the package would close a cycle through it.
"""

__version__ = "0.1.0"
