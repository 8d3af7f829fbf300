"""Robot description sources: ROS packages without ROS, URIs, xacro expansion."""
