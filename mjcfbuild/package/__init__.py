"""A Menagerie-grade model folder (``output.package: true``): the model formatted the way MuJoCo
Menagerie formats its models, its scene and assets, a README saying where it comes from, the
description's LICENSE, a CHANGELOG kept across builds and a picture."""
