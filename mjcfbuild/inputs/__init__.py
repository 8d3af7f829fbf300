"""MuJoCo inputs: what users add to the model beyond the URDF, in the reference converter's
``<mujoco_inputs>`` format (in the URDF or a separate file) or in robot.yaml."""
