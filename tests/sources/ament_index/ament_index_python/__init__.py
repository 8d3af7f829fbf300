"""The part of ROS 2's ament_index_python that xacro's ``$(find pkg)`` calls, for running the
real ``xacro`` command in tests without a ROS install (ament_index_python is not on PyPI).

It follows the ament resource index's layout: package ``name`` is installed under the first
prefix of ``AMENT_PREFIX_PATH`` holding ``share/ament_index/resource_index/packages/<name>``,
and its share folder is ``<prefix>/share/<name>``.
"""
