/* The joint kinds' tables (joint.h): the one place in the kernels that knows which kinds exist. */
#include "flexbeam.h"

static const fb_joint_ops *const KINDS[FB_JOINT_KINDS] = {
    [FB_JOINT_REVOLUTE] = &fb_joint_revolute,
    [FB_JOINT_FREE] = &fb_joint_free,
};

const fb_joint_ops *fb_joint(const fb_model *m) { return KINDS[m->joint]; }
