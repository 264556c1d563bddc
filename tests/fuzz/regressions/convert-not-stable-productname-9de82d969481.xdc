<!-- A configured device in CANopenEditor's style: ProfileHeader, ProfileBody and the object list
     entries unqualified (xmlns=""), the rest prefixed; values only in the referenced parameters. -->
<ISO15745ProfileContainer xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.canopen.org/xml/1.1">
  <ISO15745Profile>
    <ProfileHeader xmlns="">
    </ProfileHeader>
    <ProfileBody xmlns:q1="http://www.canopen.org/xml/1.1" xsi:type="q1:ProfileBody_Device_CANopen" fileName="editor-style.xdc" fileCreator="odgen tests" fileCreationDate="2024-03-05" fileCreationTime="00:30:00.0000000+01:00" fileModifiedBy="someone" fileModificationDate="2024-12-31" fileModificationTime="23:59:59.9000000+01:00" fileVersion="1" xmlns="">
      <q1:DeviceIdentity>
        <q1:productName>Configured ;node</q1:productName>
      </q1:DeviceIdentity>
      <q1:ApplicationProcess>
        <q1:dataTypeList>
          <q1:array name="Outputs" uniqueID="UID_ARR_6200">
          </q1:array>
        </q1:dataTypeList>
        <q1:parameterList>
          </q1:parameterList>
      </q1:ApplicationProcess>
    </ProfileBody>
  </ISO15745Profile>
  <ISO15745Profile>
    <ProfileHeader xmlns="">
    </ProfileHeader>
    <ProfileBody xmlns:q2="http://www.canopen.org/xml/1.1" xsi:type="q2:ProfileBody_CommunicationNetwork_CANopen" fileName="editor-style.xdc" xmlns="">
      <ApplicationLayers>
        <q2:CANopenObjectList>
        </q2:CANopenObjectList>
      </ApplicationLayers>
      <NetworkManagement>
      </NetworkManagement>
    </ProfileBody>
  </ISO15745Profile>
</ISO15745ProfileContainer>
