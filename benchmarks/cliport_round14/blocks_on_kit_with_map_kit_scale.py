import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksOnKitWithMapKitScale(Task):
    """Place three small blocks onto the three slots of the kit, left to right."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the blocks on the kit"
        self.task_completed_desc = "done kitting blocks."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        # Add kit.
        kit_size = (0.28, 0.2, 0.005)
        kit_pose = self.get_random_pose(env, kit_size)
        env.add_object('kitting/kit.urdf', kit_pose, 'fixed')

        # Scale of the objects (GenSim helper).
        scale = utils.map_kit_scale((0.3, 0.3, 0.3))
        block_size = (0.04, 0.04, 0.04)

        # Slots on the kit.
        slot_offsets = [(-0.08, 0, 0.025), (0, 0, 0.025), (0.08, 0, 0.025)]
        targ_poses = [(utils.apply(kit_pose, offset), kit_pose[1]) for offset in slot_offsets]

        colors = ['red', 'green', 'blue']
        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color]))

        self.add_goal(objs=blocks, matches=np.eye(3), targ_poses=targ_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
