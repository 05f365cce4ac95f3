// A user's own joint whose motion object lacks a member (its project): the
// scene refuses it with one static_assert naming the joint and the member,
// not an error deep inside a pass. The joint is joint_lacks_member.cpp's.
#define FLANGE_KO_PROJECT
#include "joint_lacks_member.cpp"
