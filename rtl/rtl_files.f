rtl/sync_2ff.v
rtl/adc_spi.v
