// mpc_items.vh: item kinds of the MPC core's operand pipeline (mpc_core issues them,
// mpc_operand executes them; see docs/blocks/mpc_core.md "Pipeline and latency").
`ifndef MPC_ITEMS_VH
`define MPC_ITEMS_VH
`define MPC_K_NONE 4'd0     // nothing
`define MPC_K_YC   4'd1     // copy y[o] into the scratch RAM
`define MPC_K_EBA  4'd2     // inc[o] = sat40(w_k[o] - y[o]), clamp decision against ebar_lim[o]
`define MPC_K_WN   4'd3     // wn = sat18(rshift_round(omega, ws))
`define MPC_K_LO   4'd4     // wn = max(wn, wn_min)
`define MPC_K_HI   4'd5     // wn = min(wn, wn_max)
`define MPC_K_COL  4'd6     // column operand a_j (descriptor from the coefficient memory)
`define MPC_K_UR   4'd7     // u_raw[i] = sat24(u_prev[i] + du[i]), op = u18[i]
`define MPC_K_UMX  4'd8     // op = u_max (and the lanes' wn register := u_max)
`define MPC_K_NUMX 4'd9     // op = -u_max
`define MPC_K_EBB  4'd10    // ebar[o] = sat40(ebar_prev[o] + clamp(inc[o]))
`endif
