// GLSL side of the shared kernel code: buffer declarations named as the kernels use them, and
// the macros that the C++ twin defines differently (kernels_ref/cpu_kernels.cpp).
#extension GL_GOOGLE_include_directive : require
#include "repose_shared.h"

layout(local_size_x_id = 0) in;

#define FN
#define INOUT(T) inout T
#define OUT(T) out T
#define KERNEL(name) void name(
#define KFN(ret, name) ret name(
#define KB

layout(std430, set = 0, binding = kBindPos) buffer PosBuf { vec4 B_pos[]; };
layout(std430, set = 0, binding = kBindVel) buffer VelBuf { vec4 B_vel[]; };
layout(std430, set = 0, binding = kBindOmega) buffer OmegaBuf { vec4 B_omega[]; };
layout(std430, set = 0, binding = kBindForce) buffer ForceBuf { vec4 B_force[]; };
layout(std430, set = 0, binding = kBindTorque) buffer TorqueBuf { vec4 B_torque[]; };
layout(std430, set = 0, binding = kBindPosAtBuild) buffer PosBuildBuf { vec4 B_pos_at_build[]; };
layout(std430, set = 0, binding = kBindMaterial) buffer MaterialBuf { uint B_material[]; };
layout(std430, set = 0, binding = kBindPairs) buffer PairBuf { PairParams B_pairs[]; };
layout(std430, set = 0, binding = kBindWalls) buffer WallBuf { WallState B_walls[]; };
layout(std430, set = 0, binding = kBindControl) buffer ControlBuf { uint B_control[]; };
layout(std430, set = 0, binding = kBindCellOf) buffer CellOfBuf { uint B_cell_of[]; };
layout(std430, set = 0, binding = kBindCellStart) buffer CellStartBuf { uint B_cell_start[]; };
layout(std430, set = 0, binding = kBindCellFill) buffer CellFillBuf { uint B_cell_fill[]; };
layout(std430, set = 0, binding = kBindSorted) buffer SortedBuf { uint B_sorted[]; };
layout(std430, set = 0, binding = kBindRowStart) buffer RowStartBuf { uint B_row_start[]; };
layout(std430, set = 0, binding = kBindPartner) buffer PartnerBuf { uint B_partner[]; };
layout(std430, set = 0, binding = kBindOwner) buffer OwnerBuf { uint B_owner[]; };
layout(std430, set = 0, binding = kBindHistory) buffer HistoryBuf { vec4 B_history[]; };
layout(std430, set = 0, binding = kBindOldRowStart) buffer OldRowStartBuf { uint B_old_row_start[]; };
layout(std430, set = 0, binding = kBindOldPartner) buffer OldPartnerBuf { uint B_old_partner[]; };
layout(std430, set = 0, binding = kBindOldHistory) buffer OldHistoryBuf { vec4 B_old_history[]; };
layout(std430, set = 0, binding = kBindContactForce) buffer ContactForceBuf { vec4 B_contact_force[]; };
layout(std430, set = 0, binding = kBindTorqueI) buffer TorqueIBuf { vec4 B_torque_i[]; };
layout(std430, set = 0, binding = kBindTorqueJ) buffer TorqueJBuf { vec4 B_torque_j[]; };
layout(std430, set = 0, binding = kBindTransStart) buffer TransStartBuf { uint B_trans_start[]; };
layout(std430, set = 0, binding = kBindTransFill) buffer TransFillBuf { uint B_trans_fill[]; };
layout(std430, set = 0, binding = kBindTransList) buffer TransListBuf { uint B_trans_list[]; };
layout(std430, set = 0, binding = kBindWallForce) buffer WallForceBuf { vec4 B_wall_force[]; };
layout(std430, set = 0, binding = kBindBodies) buffer BodyBuf { Body B_bodies[]; };
layout(std430, set = 0, binding = kBindSubSpheres) buffer SubSphereBuf { SubSphere B_subs[]; };
layout(std430, set = 0, binding = kBindRollingSpring) buffer RollingSpringBuf { vec4 B_rolling_spring[]; };

#ifndef REPOSE_SCAN_PUSH
layout(push_constant) uniform PushBlock { SimPush PC; };
#endif
