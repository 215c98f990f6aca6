"""Forward kinematics of a robot from Python and a matplotlib figure of its rods.

    python3 fk_plot.py models/stewart_gough.urdf fk.png
"""
import sys

import matplotlib.pyplot as plt

import pcr

model = pcr.load_model(sys.argv[1])
fk = pcr.ForwardKinematics(model)
result = fk.solve({model.input_names[0]: model.default_inputs[0] + 0.05})  # feed the first rod 5 cm
print(result.summary)
ax = plt.figure(figsize=(6, 6)).add_subplot(projection="3d")
for rod in result.rods:
    x, y, z = rod.centerline.T
    ax.plot(x, y, z, label="%s: %.3f N" % (rod.name, rod.axial_force))
for pose in result.platforms:
    ax.scatter(*pose.position, color="k")
ax.set_xlabel("x [m]"); ax.set_ylabel("y [m]"); ax.set_zlabel("z [m]")
ax.set_title("%s, %s" % (model.name, result.summary.status))
ax.legend(fontsize=7)
plt.savefig(sys.argv[2] if len(sys.argv) > 2 else "fk.png", dpi=120)
