import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlockBridgeOverTwoBlocks(Task):
    """Build a bridge: two blue blocks as pillars and a long red box across them."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "build a bridge with the blue blocks and the red box"
        self.task_completed_desc = "done building the bridge."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        base_size = (0.16, 0.06, 0.04)
        base_pose = self.get_random_pose(env, base_size)

        block_size = (0.04, 0.04, 0.04)
        pillars = []
        for _ in range(2):
            pose = self.get_random_pose(env, block_size)
            pillars.append(env.add_object('block/block.urdf', pose, color=utils.COLORS['blue']))

        beam_size = (0.14, 0.04, 0.02)
        beam_urdf = self.fill_template('box/box-template.urdf', {'DIM': beam_size})
        beam_pose = self.get_random_pose(env, beam_size)
        beam = env.add_object(beam_urdf, beam_pose, color=utils.COLORS['red'])

        pillar_targs = [(utils.apply(base_pose, (-0.05, 0, 0.02)), base_pose[1]),
                        (utils.apply(base_pose, (0.05, 0, 0.02)), base_pose[1])]
        beam_targ = (utils.apply(base_pose, (0, 0, 0.05)), base_pose[1])

        self.add_goal(objs=pillars, matches=np.ones((2, 2)), targ_poses=pillar_targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal="place the blue blocks as the pillars of the bridge")
        self.add_goal(objs=[beam], matches=np.ones((1, 1)), targ_poses=[beam_targ], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      symmetries=[np.pi], language_goal="place the red box across the pillars")
