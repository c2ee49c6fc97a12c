sim/adc_spi_slave.v
sim/adc_spi_tb.v
sim/pwm_center_sync2.v
sim/mpc_core_stream.v
sim/emc_regs_tb.v
sim/quad_gen.v
sim/cosim_top.v
sim/ctrl_seq_tb.v
